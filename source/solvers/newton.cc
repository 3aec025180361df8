#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/base/timing.h>
#include <tissuefem/solvers/newton.h>

#include <chrono>
#include <cmath>
#include <iostream>

namespace tissuefem::solvers
{
  void
  NewtonParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Newton solver");
    prm.declare_entry("Maximum iterations",
                      "25",
                      Patterns::Integer(1, 1000),
                      "Newton iterations per (attempted) step before the step "
                      "counts as failed.");
    prm.declare_entry("Absolute residual tolerance",
                      "1e-10",
                      Patterns::Double(0),
                      "Converged when the l2 norm of the nodal residual (force "
                      "units) is at most this.");
    prm.declare_entry("Relative residual tolerance",
                      "1e-10",
                      Patterns::Double(0, 1),
                      "Converged when the residual norm is at most this times "
                      "the first residual norm of the step.");
    prm.declare_entry("Update tolerance",
                      "1e-12",
                      Patterns::Double(0),
                      "Converged when the l2 norm of the Newton update (length "
                      "units) is at most this times (1 + |u|).");
    prm.declare_entry("Line search steps",
                      "8",
                      Patterns::Integer(0, 50),
                      "Halvings of the Newton update tried while the residual "
                      "norm does not decrease; the last one is taken even if "
                      "it does not. 0 takes full steps.");
    prm.declare_entry(
      "Lift boundary increments",
      "true",
      Patterns::Bool(),
      "Start each step with one Newton iteration that takes the change of "
      "the prescribed displacements as inhomogeneous constraints of the "
      "update, so the boundary motion spreads into the body through the "
      "Jacobian (as FEniCS and FEBio do). 'false' writes the new boundary "
      "values into the initial guess, which distorts the layer of elements "
      "next to a moving boundary and can cost several damped iterations.");
    prm.declare_entry("Verbose",
                      "false",
                      Patterns::Bool(),
                      "Print every iteration: residual norm (force units), "
                      "update norm (length units) and line-search step.");
    prm.leave_subsection();
  }


  void
  NewtonParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Newton solver");
    max_iterations              = prm.get_integer("Maximum iterations");
    absolute_residual_tolerance = prm.get_double("Absolute residual tolerance");
    relative_residual_tolerance = prm.get_double("Relative residual tolerance");
    update_tolerance            = prm.get_double("Update tolerance");
    max_line_search_steps       = prm.get_integer("Line search steps");
    verbose                     = prm.get_bool("Verbose");
    lift_boundary_increments    = prm.get_bool("Lift boundary increments");
    prm.leave_subsection();
  }


  NewtonResult
  solve_newton(
    const NewtonParameters &parameters,
    VectorType             &u,
    const std::function<void(const VectorType &, VectorType &, bool)> &assemble,
    const std::function<void(VectorType &, const VectorType &)> &solve_jacobian)
  {
    using Clock = std::chrono::steady_clock;
    NewtonResult result;
    VectorType   residual, update, trial, trial_residual, rhs;
    update.reinit(u);
    trial.reinit(u);
    rhs.reinit(u);

    auto timed_assemble
      = [&](const VectorType &x, VectorType &r, const bool jacobian) {
          const auto start = Clock::now();
          assemble(x, r, jacobian);
          result.assembly_seconds += seconds_since(start);
        };

    try
      {
        timed_assemble(u, residual, true);
      }
    catch (const SolverError &e)
      {
        result.failure = e.what();
        return result;
      }
    double norm = checked_l2_norm(residual);
    result.residual_norms.push_back(norm);
    const double first_norm = norm;

    while (true)
      {
        if (!std::isfinite(norm))
          {
            result.failure = "residual is not finite";
            return result;
          }
        if (norm <= parameters.absolute_residual_tolerance
            || (result.iterations > 0
                && norm <= parameters.relative_residual_tolerance * first_norm))
          {
            result.converged = true;
            return result;
          }
        if (result.iterations == parameters.max_iterations)
          {
            result.failure
              = "no convergence in " + std::to_string(parameters.max_iterations)
                + " iterations (residual norm " + std::to_string(norm) + ")";
            return result;
          }

        rhs.equ(-1., residual);
        const auto start = Clock::now();
        try
          {
            solve_jacobian(update, rhs);
          }
        catch (const SolverError &e)
          {
            result.failure = e.what();
            return result;
          }
        result.solve_seconds += seconds_since(start);
        ++result.iterations;

        // Backtracking: accept the first step length that lowers |R| (or the
        // full step when the line search is off).
        double alpha    = 1;
        bool   accepted = false;
        for (unsigned int k = 0; k <= parameters.max_line_search_steps; ++k)
          {
            trial = u;
            trial.add(alpha, update);
            try
              {
                // The Jacobian is assembled with the trial residual: the full
                // step is almost always accepted, and then it is the one the
                // next iteration needs.
                timed_assemble(trial, trial_residual, true);
                const double trial_norm = checked_l2_norm(trial_residual);
                if (std::isfinite(trial_norm)
                    && (trial_norm < norm
                        || parameters.max_line_search_steps == 0
                        || k == parameters.max_line_search_steps))
                  {
                    accepted = std::isfinite(trial_norm);
                    break;
                  }
              }
            catch (const SolverError &e)
              {
                result.failure = e.what();
              }
            alpha *= 0.5;
          }
        if (!accepted)
          {
            if (result.failure.empty())
              result.failure = "line search found no admissible step";
            return result;
          }
        result.failure.clear();
        u = trial;
        residual.swap(trial_residual);
        norm = checked_l2_norm(residual);
        result.residual_norms.push_back(norm);
        if (parameters.verbose)
          std::cout << "    Newton " << result.iterations << ": |R| = " << norm
                    << ", |du| = " << checked_l2_norm(update) << ", step "
                    << alpha << std::endl;

        if (alpha == 1
            && checked_l2_norm(update)
                 <= parameters.update_tolerance * (1 + checked_l2_norm(u)))
          {
            result.converged = std::isfinite(norm);
            return result;
          }
      }
  }
} // namespace tissuefem::solvers
