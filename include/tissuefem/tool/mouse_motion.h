#pragma once

#include <deal.II/base/tensor.h>

namespace tissuefem::tool
{
  using namespace dealii;

  /**
   * What the live view's mouse moves (held vertices, a contact tool)
   * follows: a displacement that goes towards the target the page asks,
   * by at most a given length per step and linearly over the step, so
   * that a fast mouse neither tears the mesh nor stalls the solver (the
   * same bound as a device on the live port).
   */
  template <int dim>
  class MouseMotion
  {
  public:
    /// Stands at @p at from now on.
    void
    reset(const Tensor<1, dim> &at = Tensor<1, dim>());

    /// The next step ends at @p time: from where the last one ended
    /// towards @p target, by at most @p largest_move (length units).
    void
    advance(const double          time,
            const Tensor<1, dim> &target,
            const double          largest_move);

    /// The displacement at @p time (length units).
    Tensor<1, dim>
    operator()(const double time) const;

  private:
    /// Over the step [t0, t1]: from d0 to d1.
    double         t0 = 0, t1 = 0;
    Tensor<1, dim> d0, d1;
  };
} // namespace tissuefem::tool
