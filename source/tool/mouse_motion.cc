#include <tissuefem/tool/mouse_motion.h>

namespace tissuefem::tool
{
  template <int dim>
  void
  MouseMotion<dim>::reset(const Tensor<1, dim> &at)
  {
    d0 = d1 = at;
  }


  template <int dim>
  void
  MouseMotion<dim>::advance(const double          time,
                            const Tensor<1, dim> &target,
                            const double          largest_move)
  {
    t0                   = t1;
    t1                   = time;
    d0                   = d1;
    Tensor<1, dim> delta = target - d0;
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
