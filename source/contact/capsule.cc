#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/contact/capsule.h>

#include <algorithm>

namespace tissuefem::contact
{
  template <int dim>
  void
  Capsule<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("capsule");
    prm.declare_entry("Start",
                      "0, 0, 0",
                      Patterns::Anything(),
                      "One end of the axis segment, the centre of one "
                      "rounded end (length units; the first dim "
                      "coordinates are used).");
    prm.declare_entry("End",
                      "0, 1, 0",
                      Patterns::Anything(),
                      "The other end of the axis segment, the centre of the "
                      "other rounded end (the tip); it may equal 'Start' "
                      "(a sphere).");
    prm.declare_entry("Radius",
                      "0.1",
                      Patterns::Double(0, Patterns::Double::max_double_value),
                      "The shaft's radius (length units, > 0).");
    prm.leave_subsection();
  }


  template <int dim>
  Capsule<dim>::Capsule(ParameterHandler &prm)
  {
    prm.enter_subsection("capsule");
    start = parse_leading_point<dim>(prm.get("Start"), "capsule/Start");
    const Point<dim> end
      = parse_leading_point<dim>(prm.get("End"), "capsule/End");
    radius = prm.get_double("Radius");
    prm.leave_subsection();
    require(radius > 0, "capsule/Radius", "must be positive");
    length = (end - start).norm();
    if (length > 0)
      axis = (end - start) / length;
  }


  template <int dim>
  Gap<dim>
  Capsule<dim>::gap(const Point<dim> &y) const
  {
    // The nearest point of the axis segment, c = start + s axis.
    const double         s = std::clamp((y - start) * axis, 0., length);
    const Tensor<1, dim> r = y - (start + s * axis);
    const double         d = r.norm();
    Gap<dim>             result;
    result.distance = d - radius;
    if (d == 0)
      {
        // On the axis every direction across it is nearest: one of them,
        // and no curvature term.
        Tensor<1, dim> e;
        e[dim - 1] = 1;
        if (std::abs(e * axis) > 0.9)
          {
            e[dim - 1] = 0;
            e[0]       = 1;
          }
        e -= (e * axis) * axis;
        if (e.norm() == 0) // 1D: across the axis is nowhere.
          e[0] = 1;
        result.normal = e / e.norm();
        return result;
      }
    result.normal            = r / d;
    Tensor<2, dim> projector = unit_symmetric_tensor<dim>()
                               - outer_product(result.normal, result.normal);
    // Along the shaft (strictly between the ends) the axis direction is
    // flat.
    if (s > 0 && s < length)
      projector -= outer_product(axis, axis);
    result.normal_gradient = projector / d;
    return result;
  }


  template <int dim>
  double
  Capsule<dim>::distance(const Point<dim> &y) const
  {
    const double s = std::clamp((y - start) * axis, 0., length);
    return (y - (start + s * axis)).norm() - radius;
  }


  template <int dim>
  Drawing<dim>
  Capsule<dim>::drawing(const Point<dim> &, const double) const
  {
    // A capsule of length 0 (a ball) has no axis of its own.
    Tensor<1, dim> direction = axis;
    if (length == 0)
      direction[dim - 1] = 1;
    return drawing::revolve(drawing::capsule_profile(length, radius),
                            start,
                            direction);
  }


  template class Capsule<1>;
  template class Capsule<2>;
  template class Capsule<3>;

  TISSUEFEM_REGISTER_SHAPE(
    Capsule,
    "capsule",
    "a segment thickened by a radius (an instrument's shaft with a rounded "
    "tip; a stadium in 2D).")
} // namespace tissuefem::contact
