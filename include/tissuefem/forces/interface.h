#pragma once

#include <deal.II/lac/affine_constraints.h>

#include <tissuefem/base/parallel.h>

namespace tissuefem::forces
{
  using namespace dealii;

  /**
   * A force on the solid that does not come from its elements, derived
   * from a potential E(u, t): contact with a rigid obstacle, for example.
   * The solid's assembly adds dE/du to its residual (which is M a + f_int
   * - f_ext, so a force f = -dE/du on the body enters with the right sign)
   * and, for Newton, d2E/du2 to its Jacobian; the implicit energy that the
   * line search and the trust region minimize adds E. Each contribution is
   * one file pair; the scene hands it to the solid
   * (Solid::add_force_contribution()).
   *
   * Every process calls every function. u is the ghosted displacement of
   * the solid's current mesh: a contribution reads the mesh from the
   * discretization at each call, so that mesh changes need no signal.
   */
  template <int dim>
  class Interface
  {
  public:
    virtual ~Interface() = default;

    /**
     * Adds dE/du at (@p u, @p time) to @p residual and, with @p jacobian,
     * d2E/du2 to @p matrix, through @p rows as the cell assembly does
     * (with @p inhomogeneous as it). The caller compresses both.
     */
    virtual void
    add(const VectorType                &u,
        const double                     time,
        const bool                       jacobian,
        const AffineConstraints<double> &rows,
        const bool                       inhomogeneous,
        MatrixType                      &matrix,
        VectorType                      &residual) const = 0;

    /// E(u, t) (energy units), summed over the processes.
    virtual double
    energy(const VectorType &u, const double time) const = 0;

    /// Whether E depends on t itself (a moving obstacle): then a quasistatic
    /// step that fails may succeed when shorter.
    virtual bool
    changes_with_time() const
    {
      return false;
    }
  };
} // namespace tissuefem::forces
