#include <tissuefem/tool/mouse_motion.h>

#include <cmath>

namespace tissuefem::tool
{
  template <int dim>
  void
  MouseMotion<dim>::scale(const double body_diameter)
  {
    diameter = body_diameter;
  }


  template <int dim>
  std::string
  MouseMotion<dim>::refusal(const Tensor<1, dim> &target,
                            const std::string    &what) const
  {
    for (unsigned int d = 0; d < dim; ++d)
      if (!std::isfinite(target[d]))
        return what + " is not finite";
    if (target.norm() > diameter)
      return what + " farther than the body's diameter";
    return {};
  }


  template <int dim>
  void
  MouseMotion<dim>::reset(const Tensor<1, dim> &at)
  {
    d0 = d1 = at;
  }


  template <int dim>
  void
  MouseMotion<dim>::advance(const double time, const Tensor<1, dim> &target)
  {
    const double largest_move = 0.1 * diameter;
    t0                        = t1;
    t1                        = time;
    d0                        = d1;
    Tensor<1, dim> delta      = target - d0;
    if (delta.norm() > largest_move)
      delta *= largest_move / delta.norm();
    d1 = d0 + delta;
  }


  template <int dim>
  Tensor<1, dim>
  MouseMotion<dim>::operator()(const double time) const
  {
    if (time <= t0 || t1 <= t0)
      return time < t1 ? d0 : d1;
    if (time >= t1)
      return d1;
    return d0 + (time - t0) / (t1 - t0) * (d1 - d0);
  }

  template class MouseMotion<1>;
  template class MouseMotion<2>;
  template class MouseMotion<3>;
} // namespace tissuefem::tool
