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
    bool lift_boundary_increments;
    bool verbose;
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
   * times the first |R|, or |du| <= update tolerance (1 + |u|), with R
   * evaluated at the new iterate.
   */
  NewtonResult
  solve_newton(
    const NewtonParameters &parameters,
    VectorType             &u,
    const std::function<void(const VectorType &, VectorType &, bool)> &assemble,
    const std::function<void(VectorType &, const VectorType &)> &solve_jacobian,
    const std::function<double(const VectorType &)>             &energy = {});
} // namespace tissuefem::solvers
