// Meshes read from files: VTU by tissuefem's reader, Gmsh, legacy VTK and
// Abaqus by deal.II's GridIn.
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/geometry/mesh_check.h>
#include <tissuefem/geometry/source.h>
#include <tissuefem/geometry/vtu_reader.h>

#include <filesystem>
#include <fstream>

namespace tissuefem::geometry
{
  namespace
  {
    /// Gmsh, legacy VTK and Abaqus files through deal.II's GridIn.
    template <int dim>
    void
    read_with_grid_in(const std::string  &file,
                      const std::string  &extension,
                      Triangulation<dim> &triangulation)
    {
      GridIn<dim>      grid_in(triangulation);
      std::ifstream    in(file);
      const GmshSurvey survey
        = extension == ".msh" ? survey_gmsh(file, dim) : GmshSurvey();
      // A cell that lists a node twice has no volume; refused before the
      // reader builds it (deal.II's connectivity asserts on it in debug
      // builds, and a release build would leave it to the mesh check).
      if (!survey.repeated_node_elements.empty())
        throw InputError(
          "Mesh file '" + file
          + "': " + std::to_string(survey.repeated_node_elements.size())
          + " degenerate cells (zero volume: an element lists a node "
            "twice), the first: element number "
          + std::to_string(survey.repeated_node_elements[0]));
      try
        {
          if (extension == ".msh")
            grid_in.read_msh(in);
          else if (extension == ".vtk")
            grid_in.read_vtk(in);
          else if (extension == ".inp")
            grid_in.read_abaqus(in);
          else
            throw InputError("Parameter 'Geometry/Mesh file': unknown "
                             "extension '"
                             + extension + "' of '" + file
                             + "' (use .msh, .vtk, .vtu or .inp)");
        }
      catch (const ExceptionBase &e)
        {
          throw InputError("Mesh file '" + file
                           + "' could not be read: " + one_line_message(e));
        }
      if (survey.inverted > 0)
        parallel_tools::screen()
          << "Mesh file '" << file << "': " << survey.inverted
          << " cells had their vertices in inverted order (negative volume) "
             "and were reoriented by the reader (a safe repair: the cell is "
             "the same)."
          << std::endl;
      if (!survey.repeated_numbers.empty())
        parallel_tools::screen()
          << "Mesh file '" << file << "': "
          << (survey.repeated_numbers.size() == 1
                ? "element number "
                : std::to_string(survey.repeated_numbers.size())
                    + " element numbers are repeated, the first: ")
          << survey.repeated_numbers[0] << " is used by "
          << survey.repeated_uses[0]
          << " elements; the numbers carry no meaning here (cells are "
             "numbered anew), so every element is kept."
          << std::endl;
    }
  } // namespace


  /**
   * 'Mesh file', chosen by extension, checked (mesh_check.h) and scaled by
   * 'Scale'; cells and faces keep the ids the file carries.
   */
  template <int dim>
  class MeshFile : public Source<dim>
  {
  public:
    void
    build(const GeometryParameters &parameters,
          Triangulation<dim>       &triangulation) const override
    {
      const std::string &file = parameters.mesh_file;
      require(!file.empty(), "Geometry/Mesh file", "is empty");
      require(std::filesystem::is_regular_file(file),
              "Geometry/Mesh file",
              "cannot open '" + file + "'");
      const std::string extension = std::filesystem::path(file).extension();
      if (extension == ".vtu")
        read_vtu(file, triangulation);
      else
        read_with_grid_in(file, extension, triangulation);
      require(triangulation.n_active_cells() > 0,
              "Geometry/Mesh file",
              "'" + file + "' holds no cells of dimension "
                + std::to_string(dim));
      check_mesh(triangulation, file);
      if (parameters.scale != 1.)
        GridTools::scale(parameters.scale, triangulation);
    }
  };
} // namespace tissuefem::geometry

namespace
{
  using tissuefem::geometry::MeshFile;
}
TISSUEFEM_REGISTER_GEOMETRY_SOURCE(
  MeshFile,
  "file",
  "read 'Mesh file' (see there for the formats), scaled by 'Scale'.")
