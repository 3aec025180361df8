#pragma once

#include <deal.II/lac/affine_constraints.h>

#include <tissuefem/base/parallel.h>

#include <string>

namespace tissuefem::solid
{
  using namespace dealii;

  /// What a contribution's multiplier update found
  /// (ForceContribution::augment()).
  enum class Augmentation
  {
    /// Its constraints hold to their tolerance: the step is done.
    satisfied,
    /// The multipliers moved: the step is solved again with them.
    again,
    /// It gave up (the message says why): the step failed.
    failed
  };

  /**
   * A force on the solid that does not come from its elements, derived
   * from a potential E(u, t): contact with a rigid obstacle, for example.
   * The solid's assembly adds dE/du to its residual (which is M a + f_int
   * - f_ext, so a force f = -dE/du on the body enters with the right sign)
   * and, for Newton, d2E/du2 to its Jacobian; the implicit energy that the
   * line search and the trust region minimize adds E. Each contribution is
   * one file pair, registered with TISSUEFEM_REGISTER_FORCE_CONTRIBUTION
   * (forces/registry.h); the scene creates those the file asks for and
   * hands them to the solid (Solid::add_force_contribution()).
   *
   * Every process calls every function. u is the ghosted displacement of
   * the solid's current mesh: a contribution reads the mesh from the
   * discretization at each call, so that mesh changes need no signal.
   */
  template <int dim>
  class ForceContribution
  {
  public:
    virtual ~ForceContribution() = default;

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

    /**
     * For explicit steps: adds to @p row_sums (an assembly vector; the
     * caller compresses it), per degree of freedom, a bound on the row sum
     * of |d2E/du2| this contribution can reach in any state (Gershgorin's
     * bound, which with the lumped mass bounds the highest frequency it
     * adds). None by default.
     */
    virtual void
    add_stiffness_bound(VectorType &row_sums) const
    {
      (void)row_sums;
    }

    /**
     * After Newton has converged at the ghosted displacement @p u at
     * @p time, for the @p update-th time in this step (from 0): a
     * contribution that enforces a constraint with multipliers (the
     * augmented Lagrangian's Uzawa update) updates them and says whether
     * the step must be solved again, with the reason in @p message if it
     * gives up. A plain penalty has nothing to update.
     */
    virtual Augmentation
    augment(const VectorType  &u,
            const double       time,
            const unsigned int update,
            std::string       &message)
    {
      (void)u;
      (void)time;
      (void)update;
      (void)message;
      return Augmentation::satisfied;
    }

    /// At the start of each attempt at an implicit step, from the ghosted
    /// @p u at @p time: a contribution with history (friction's stick
    /// points) notes where the step starts.
    virtual void
    begin_step(const VectorType &u, const double time)
    {
      (void)u;
      (void)time;
    }

    /// When a step has been accepted at the ghosted @p u at @p time: a
    /// contribution with history commits it.
    virtual void
    accept_step(const VectorType &u, const double time)
    {
      (void)u;
      (void)time;
    }

    /// Whether it may hold a body against rigid motion (an obstacle the
    /// body rests on), so that a quasistatic scene need not fix every
    /// part by a Dirichlet boundary.
    virtual bool
    may_hold_body() const
    {
      return false;
    }

    /// Whether E depends on t itself (a moving obstacle): then a quasistatic
    /// step that fails may succeed when shorter.
    virtual bool
    changes_with_time() const
    {
      return false;
    }
  };
} // namespace tissuefem::solid
