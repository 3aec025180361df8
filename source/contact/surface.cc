#include <tissuefem/base/input_error.h>
#include <tissuefem/contact/surface.h>

#include <filesystem>

namespace tissuefem::contact
{
  template <int dim>
  void
  Surface<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("surface");
    prm.declare_entry(
      "File",
      "",
      Patterns::Anything(),
      "A closed, consistently oriented triangulated surface: .stl (ASCII or "
      "binary) or .obj (polygons are split into triangles). A relative path "
      "is taken relative to the parameter file's directory. Dimension 3 "
      "only. Open or inconsistently oriented surfaces are refused, naming "
      "the edges; one oriented inward throughout is turned outward.");
    prm.declare_entry("Scale",
                      "1",
                      Patterns::Double(0),
                      "Factor applied to the file's coordinates, to convert "
                      "its length unit (> 0).");
    prm.leave_subsection();
  }


  template <int dim>
  Surface<dim>::Surface(ParameterHandler &prm, const std::string &directory)
  {
    prm.enter_subsection("surface");
    std::string  file  = Utilities::trim(prm.get("File"));
    const double scale = prm.get_double("Scale");
    prm.leave_subsection();
    require(dim == 3,
            "surface/File",
            "a triangulated surface needs Dimension = 3");
    require(!file.empty(), "surface/File", "names no file");
    require(scale > 0, "surface/Scale", "must be > 0");
    if (std::filesystem::path(file).is_relative() && !directory.empty())
      file = (std::filesystem::path(directory) / file).string();
    surface = std::make_shared<const TriangleSurface>(
      TriangleSurface::read(file, "surface/File", scale));
  }


  template <int dim>
  Gap<dim>
  Surface<dim>::gap(const Point<dim> &y) const
  {
    Gap<dim> result;
    if constexpr (dim == 3)
      {
        const TriangleSurface::Query q = surface->query(y);
        result.distance                = q.distance;
        result.normal                  = q.normal;
        result.normal_gradient         = q.normal_gradient;
      }
    else
      (void)y;
    return result;
  }


  template <int dim>
  Drawing<dim>
  Surface<dim>::drawing(const Point<dim> &, const double) const
  {
    Drawing<dim> result;
    if constexpr (dim == 3)
      {
        result.vertices = surface->corners();
        for (const auto &t : surface->faces())
          result.triangles.insert(result.triangles.end(), t.begin(), t.end());
      }
    return result;
  }


  template class Surface<1>;
  template class Surface<2>;
  template class Surface<3>;

  TISSUEFEM_REGISTER_SHAPE(Surface,
                           "surface",
                           "a closed triangulated surface from STL or OBJ "
                           "(3D).")
} // namespace tissuefem::contact
