#pragma once

#include <deal.II/base/tensor.h>

#include <string>

namespace tissuefem::tool
{
  using namespace dealii;

  /**
   * What the live view's mouse moves (held vertices, a contact tool)
   * follows: a displacement that goes towards the target the page asks,
   * by at most a given length per step and linearly over the step, so
   * that a fast mouse neither tears the mesh nor stalls the solver (the
   * same bound as a device on the live port). Bounds scale with the body's
   * diameter: a target of at most the diameter, a tenth of it per step.
   */
  template <int dim>
  class MouseMotion
  {
  public:
    /// Scales the bounds to a body of diameter @p diameter (length units).
    void
    scale(const double diameter);

    /// Why a page may not ask @p target (empty: it may): not finite, or
    /// farther than the body's diameter. @p what names it in the message.
    std::string
    refusal(const Tensor<1, dim> &target, const std::string &what) const;

    /// Stands at @p at from now on.
    void
    reset(const Tensor<1, dim> &at = Tensor<1, dim>());

    /// The next step ends at @p time: from where the last one ended
    /// towards @p target, by at most a tenth of the body's diameter.
    void
    advance(const double time, const Tensor<1, dim> &target);

    /// The displacement at @p time (length units).
    Tensor<1, dim>
    operator()(const double time) const;

  private:
    /// Over the step [t0, t1]: from d0 to d1.
    double         t0 = 0, t1 = 0;
    Tensor<1, dim> d0, d1;
    double         diameter = 1;
  };
} // namespace tissuefem::tool
