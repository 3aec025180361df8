#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/affine_constraints.h>
#include <tissuefem/base/parallel.h>

#include <functional>
#include <string>
#include <vector>

namespace tissuefem::solvers
{
  using namespace dealii;

  /// The 'Newton solver' subsection.
  struct NewtonParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    unsigned int max_iterations;
    double       absolute_residual_tolerance;
    double       relative_residual_tolerance;
    double       update_tolerance;
    unsigned int max_line_search_steps;
    /// Whether the line search asks for sufficient decrease of the energy
    /// (where the caller provides one) rather than of the residual norm.
    bool energy_line_search;
    /// 'Globalization = trust region': solve_trust_region() where the
    /// caller has an energy and a Jacobian product.
    bool trust_region = false;
    bool lift_boundary_increments;
    bool verbose;
    /// Whether Newton keeps the Jacobian (and its factorization or AMG
    /// hierarchy) while it contracts fast enough (modified Newton).
    bool reuse_jacobian;
    /// Whether the factorization is also kept from step to step.
    bool reuse_across_steps;
    /// The largest |R_{k+1}| / |R_k| with a kept Jacobian before it is
    /// assembled and factorized anew.
    double reuse_contraction;
    /// Converged when max |du| <= this times the body's diameter.
    double displacement_tolerance;
  };

  struct NewtonResult
  {
    bool         converged  = false;
    unsigned int iterations = 0;
    /// l2 norms of the residual (force units), one per evaluation at an
    /// accepted iterate, starting with the initial guess.
    std::vector<double> residual_norms;
    std::string         failure;
    double              assembly_seconds = 0;
    double              solve_seconds    = 0;
    /// Jacobians assembled (and factorized) by this call.
    unsigned int jacobians = 0;
  };

  /**
   * Newton's method with a backtracking line search: on the energy whose
   * gradient the residual is, where @p energy is given and 'Line search' is
   * 'energy' (Armijo's sufficient decrease E(u + a du) <= E(u) + 1e-4 a R.du,
   * step lengths from quadratic interpolation, Nocedal and Wright sec 3.5);
   * on the residual norm otherwise, and also in an iteration whose update
   * is not a descent direction (R.du >= 0, an indefinite Jacobian).
   * @p assemble(u, residual, with_jacobian) evaluates the residual (and the
   * Jacobian, kept by the caller); it may throw SolverError for a state
   * the model cannot evaluate (an inverted element), which the line search
   * treats as a failed trial. @p solve_jacobian(du, rhs) solves J du = rhs.
   * Converged when |R| <= absolute tolerance, or |R| <= relative tolerance
   * times the first |R|, or |du| <= update tolerance (1 + |u|), or max |du|
   * <= displacement tolerance times @p length_scale, with R evaluated at
   * the new iterate.
   *
   * @p solve_jacobian(du, rhs, refactorize) solves with the last assembled
   * Jacobian; with 'Jacobian reuse', Newton assembles residuals only and
   * solves with the kept factorization (refactorize false) while |R|
   * contracts by at least 'Reuse contraction' per iteration and the line
   * search takes full steps; otherwise it assembles the Jacobian at the
   * current iterate and refactorizes. @p jacobian_current says that the
   * caller has just assembled and factorized a Jacobian near @p u (the
   * first iteration may then reuse it).
   */
  /**
   * Unknowns outside u that move with it (the three-field element's cell
   * dilatations and pressures, solid::IterationUnknowns): @p predict(du)
   * after every linear solve, @p trial(alpha) before every evaluation at
   * step length alpha along du (0 back to where du started).
   */
  struct NewtonHooks
  {
    std::function<void(const VectorType &)> predict;
    std::function<void(double)>             trial;
    /// Take full steps, shortened only where a trial state cannot be
    /// evaluated (an inverted element, a non-finite residual): for
    /// iterates off a constraint, where the energy is no merit and the
    /// residual norm refuses the right steps of a stiff problem.
    bool full_steps = false;
  };

  /// @p energy at @p x, +infinity where the model cannot evaluate it (a
  /// SolverError: an inverted element), so that a globalization shortens
  /// the step; the time it took goes to @p result's assembly time.
  double
  energy_or_infinity(const std::function<double(const VectorType &)> &energy,
                     const VectorType                                &x,
                     NewtonResult                                    &result);

  /// "no convergence in N iterations (residual norm R, force units)", R in
  /// three significant digits at any size.
  std::string
  no_convergence_message(const unsigned int max_iterations, const double norm);

  NewtonResult
  solve_newton(
    const NewtonParameters &parameters,
    VectorType             &u,
    const std::function<void(const VectorType &, VectorType &, bool)> &assemble,
    const std::function<void(VectorType &, const VectorType &, bool)>
                                                    &solve_jacobian,
    const std::function<double(const VectorType &)> &energy           = {},
    const double                                     length_scale     = 0,
    const bool                                       jacobian_current = false,
    const NewtonHooks                               *hooks = nullptr);
} // namespace tissuefem::solvers
