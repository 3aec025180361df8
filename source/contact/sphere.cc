#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/contact/sphere.h>

namespace tissuefem::contact
{
  template <int dim>
  void
  Sphere<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("sphere");
    prm.declare_entry("Centre",
                      "0, 0, 0",
                      Patterns::Anything(),
                      "The centre (length units; the first dim coordinates "
                      "are used).");
    prm.declare_entry("Radius",
                      "1",
                      Patterns::Double(0, Patterns::Double::max_double_value),
                      "The radius (length units, > 0).");
    prm.leave_subsection();
  }


  template <int dim>
  Sphere<dim>::Sphere(ParameterHandler &prm)
  {
    prm.enter_subsection("sphere");
    centre = parse_leading_point<dim>(prm.get("Centre"), "sphere/Centre");
    radius = prm.get_double("Radius");
    prm.leave_subsection();
    require(radius > 0, "sphere/Radius", "must be positive");
  }


  template <int dim>
  Gap<dim>
  Sphere<dim>::gap(const Point<dim> &y) const
  {
    Gap<dim>             result;
    const Tensor<1, dim> r = y - centre;
    const double         d = r.norm();
    result.distance        = d - radius;
    if (d == 0)
      {
        // At the centre every direction is nearest: any unit normal
        // (the first axis) and no curvature term.
        result.normal[0] = 1;
        return result;
      }
    result.normal          = r / d;
    result.normal_gradient = (unit_symmetric_tensor<dim>()
                              - outer_product(result.normal, result.normal))
                             / d;
    return result;
  }


  template <int dim>
  double
  Sphere<dim>::distance(const Point<dim> &y) const
  {
    return (y - centre).norm() - radius;
  }


  template <int dim>
  Drawing<dim>
  Sphere<dim>::drawing(const Point<dim> &, const double) const
  {
    Tensor<1, dim> axis;
    axis[dim - 1] = 1;
    return drawing::revolve(drawing::capsule_profile(0, radius), centre, axis);
  }


  template class Sphere<1>;
  template class Sphere<2>;
  template class Sphere<3>;

  TISSUEFEM_REGISTER_SHAPE(Sphere,
                           "sphere",
                           "a ball (a disc in 2D; a probe's tip).")
} // namespace tissuefem::contact
