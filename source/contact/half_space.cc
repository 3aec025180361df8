#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/contact/half_space.h>

namespace tissuefem::contact
{
  template <int dim>
  void
  HalfSpace<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("half-space");
    prm.declare_entry("Point",
                      "0, 0, 0",
                      Patterns::Anything(),
                      "A point of the bounding plane (length units; the "
                      "first dim coordinates are used).");
    prm.declare_entry("Normal",
                      "0, 1, 0",
                      Patterns::Anything(),
                      "The plane's normal, pointing out of the obstacle "
                      "towards the tissue (normalized; the first dim "
                      "components are used).");
    prm.leave_subsection();
  }


  template <int dim>
  HalfSpace<dim>::HalfSpace(ParameterHandler &prm)
  {
    prm.enter_subsection("half-space");
    point  = parse_leading_point<dim>(prm.get("Point"), "half-space/Point");
    normal = parse_leading_point<dim>(prm.get("Normal"), "half-space/Normal");
    prm.leave_subsection();
    require(normal.norm() > 0, "half-space/Normal", "must not be zero");
    normal /= normal.norm();
  }


  template <int dim>
  Gap<dim>
  HalfSpace<dim>::gap(const Point<dim> &y) const
  {
    Gap<dim> result;
    result.distance = (y - point) * normal;
    result.normal   = normal;
    return result;
  }


  template <int dim>
  Drawing<dim>
  HalfSpace<dim>::drawing(const Point<dim> &centre, const double extent) const
  {
    Drawing<dim> result;
    // The foot of the centre on the plane.
    const Point<dim> foot = centre - ((centre - point) * normal) * normal;
    const double     h    = extent / 2;
    if constexpr (dim == 2)
      {
        // A band of depth extent / 10 behind a segment of the plane line.
        const Tensor<1, 2> along({-normal[1], normal[0]});
        const double       depth = extent / 10;
        result.vertices          = {foot - h * along,
                                    foot + h * along,
                                    foot + h * along - depth * normal,
                                    foot - h * along - depth * normal};
        result.triangles         = {0, 1, 2, 0, 2, 3};
        drawing::orient_outwards(result);
      }
    if constexpr (dim == 3)
      {
        // A square of the plane, seen from outside (the tissue's side):
        // (a, b, normal) right-handed.
        const auto [a, b] = drawing::tangent_frame(normal);
        result.vertices   = {foot - h * a - h * b,
                             foot + h * a - h * b,
                             foot + h * a + h * b,
                             foot - h * a + h * b};
        result.triangles  = {0, 1, 2, 0, 2, 3};
      }
    (void)foot, (void)h;
    return result;
  }


  template class HalfSpace<1>;
  template class HalfSpace<2>;
  template class HalfSpace<3>;

  TISSUEFEM_REGISTER_SHAPE(HalfSpace,
                           "half-space",
                           "everything behind a plane (a table, a floor).")
} // namespace tissuefem::contact
