#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/base/timing.h>
#include <tissuefem/solvers/newton.h>
#include <tissuefem/solvers/stopping.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

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
                      "Step-length reductions tried per Newton iteration "
                      "('Line search = residual norm': halvings while the "
                      "residual norm does not decrease; 'energy': factors "
                      "between 0.1 and 0.5 from quadratic interpolation "
                      "until Armijo's condition holds); the last one is "
                      "taken even if it fails. 0 takes full steps.");
    prm.declare_entry(
      "Line search",
      "energy",
      Patterns::Selection("energy|residual norm"),
      "What a step length must decrease: 'energy', the potential whose "
      "gradient the residual is (stored energy - external work, plus the "
      "inertial term 1/(2 dt^2) |u - u_tilde|_M^2 of implicit steps; Armijo's "
      "condition with quadratic interpolation of the step length), or "
      "'residual norm' (halvings until |R| decreases). 'energy' falls back to "
      "the residual norm where the operator has no energy or the update is "
      "no descent direction.");
    prm.declare_entry(
      "Globalization",
      "line search",
      Patterns::Selection("line search|trust region"),
      "How Newton's steps are kept from diverging. 'line search': "
      "backtracking along the Newton update (see 'Line search'). 'trust "
      "region': Powell's dogleg in a region whose radius follows how well "
      "the quadratic model predicted the energy's decrease (Nocedal and "
      "Wright 2006, ch 4; solvers/trust_region.h); where the Jacobian is "
      "indefinite (buckling, snap-through) it descends along the gradient "
      "instead of searching on the residual norm, and needs a new "
      "Jacobian every iteration. Backward Euler and quasistatic steps of "
      "elements without cell unknowns only (others use the line search).");
    prm.declare_entry(
      "Lift boundary increments",
      "true",
      Patterns::Bool(),
      "Start each step with one Newton iteration that takes the change of "
      "the prescribed displacements as inhomogeneous constraints of the "
      "update, so the boundary motion spreads into the body through the "
      "Jacobian (as FEniCS and FEBio do). In a quasistatic step the lifted "
      "guess is kept only if its energy is not above that of the guess with "
      "the new values written in (a full step of a stiff load increment can "
      "overshoot). 'false' writes the new boundary values into the initial "
      "guess, which distorts the layer of elements next to a moving "
      "boundary and can cost several damped iterations.");
    prm.declare_entry(
      "Jacobian reuse",
      "true",
      Patterns::Bool(),
      "Modified Newton: keep the Jacobian and its factorization (direct "
      "solvers) or the matrix and AMG hierarchy (cg amg) while the residual "
      "norm falls by at least 'Reuse contraction' per iteration and the "
      "line search takes full steps, assembling residuals only; otherwise "
      "assemble the Jacobian at the current iterate and factorize it. Each "
      "step starts from the Jacobian of its boundary lifting (see 'Lift "
      "boundary increments'). The answer is the same to the tolerances; "
      "a factorization costs 10-30 residual evaluations on a 3D mesh, so "
      "this saves most of them. false: a new Jacobian every iteration "
      "(Newton's quadratic convergence).");
    prm.declare_entry(
      "Jacobian reuse across steps",
      "false",
      Patterns::Bool(),
      "With 'Jacobian reuse': also keep the factorization from one step to "
      "the next while the step size stays and the steps converge, so that "
      "a step's boundary lifting solves with it instead of factorizing; "
      "Newton still makes a fresh one where it contracts too slowly. Off "
      "by default: a run continued from a checkpoint factorizes anew where "
      "the uninterrupted run would not, so the two agree only to Newton's "
      "tolerances instead of bit for bit.");
    prm.declare_entry("Reuse contraction",
                      "0.25",
                      Patterns::Double(0, 1),
                      "With 'Jacobian reuse': the largest ratio |R_k+1| / "
                      "|R_k| of residual norms accepted with a kept "
                      "Jacobian; above it the next iteration assembles "
                      "and factorizes anew. The quasi-Newton backward "
                      "Euler's update test asks for the same contraction.");
    prm.declare_entry(
      "Displacement tolerance",
      "1e-8",
      Patterns::Double(0),
      "Converged when the largest entry of a full Newton update is at most "
      "this times the diameter of the reference body (length units per "
      "length unit). With a contraction of at most 'Reuse contraction' the "
      "displacement then lies within about a third of that of the solution "
      "of the step's equations: 1e-8 is a nanometre on a 10 cm organ, far "
      "below any discretization error; a real-time scene may use 1e-5 "
      "(a micrometre) and stop an iteration or two earlier. 0: off (only "
      "the residual tests stop Newton).");
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
    energy_line_search          = prm.get("Line search") == "energy";
    trust_region                = prm.get("Globalization") == "trust region";
    verbose                     = prm.get_bool("Verbose");
    lift_boundary_increments    = prm.get_bool("Lift boundary increments");
    reuse_jacobian              = prm.get_bool("Jacobian reuse");
    reuse_contraction           = prm.get_double("Reuse contraction");
    reuse_across_steps          = prm.get_bool("Jacobian reuse across steps");
    displacement_tolerance      = prm.get_double("Displacement tolerance");
    prm.leave_subsection();
  }


  namespace
  {
    using Clock = std::chrono::steady_clock;

    /**
     * The state of one solve_newton() call: the iterate, its residual,
     * norm and energy, and the result so far. A class so that the phases
     * of an iteration (the update, the two line searches, taking the step)
     * can be functions of their own that share this state.
     */
    class NewtonIteration
    {
    public:
      NewtonIteration(
        const NewtonParameters &parameters,
        VectorType             &u,
        const std::function<void(const VectorType &, VectorType &, bool)>
          &assemble,
        const std::function<void(VectorType &, const VectorType &, bool)>
                                                        &solve_jacobian,
        const std::function<double(const VectorType &)> &energy,
        const double                                     length_scale,
        const bool                                       jacobian_current,
        const NewtonHooks                               *hooks)
          : parameters(parameters)
          , u(u)
          , assemble(assemble)
          , solve_jacobian(solve_jacobian)
          , energy(energy)
          , length_scale(length_scale)
          , hooks(hooks)
          , reuse(parameters.reuse_jacobian)
          , use_energy(parameters.energy_line_search && energy
                       && parameters.max_line_search_steps > 0)
          // With reuse, trial states get residuals only; the Jacobian is
          // assembled where it is needed (need_jacobian).
          , need_jacobian(!(reuse && jacobian_current))
      {
        update.reinit(u);
        trial.reinit(u);
        rhs.reinit(u);
      }

      NewtonResult
      run();

    private:
      const NewtonParameters &parameters;
      VectorType             &u;
      const std::function<void(const VectorType &, VectorType &, bool)>
        &assemble;
      const std::function<void(VectorType &, const VectorType &, bool)>
                                                      &solve_jacobian;
      const std::function<double(const VectorType &)> &energy;
      const double                                     length_scale;
      const NewtonHooks                               *hooks;
      const bool                                       reuse, use_energy;

      void
      set_trial(const double alpha)
      {
        if (hooks)
          hooks->trial(alpha);
      }
      bool need_jacobian;

      NewtonResult result;
      VectorType   residual, update, trial, trial_residual, rhs;
      double       norm = 0, first_norm = 0, current_energy = 0;

      /// assemble(), timed and counted in the result.
      void
      timed_assemble(const VectorType &x, VectorType &r, const bool jacobian)
      {
        const auto start = Clock::now();
        assemble(x, r, jacobian);
        result.assembly_seconds += seconds_since(start);
        if (jacobian)
          ++result.jacobians;
      }

      double
      energy_at(const VectorType &x)
      {
        return energy_or_infinity(energy, x, result);
      }

      /// Newton's residual tests (the relative one from the first
      /// iteration on).
      bool
      residual_converged() const
      {
        return norm <= parameters.absolute_residual_tolerance
               || (result.iterations > 0
                   && norm
                        <= parameters.relative_residual_tolerance * first_norm);
      }

      bool
      finished_before_iteration();

      bool
      solve_for_update();

      bool
      line_search(double &alpha);

      /// Whether line_search() took the update whole for passing the
      /// update tests (ends_newton() at the iterate it started from).
      bool whole = false;

      /// Newton's update tests: whether the full step @p du is within
      /// 'Update tolerance' or moves no node by more than 'Displacement
      /// tolerance' times the body's size.
      bool
      ends_newton(const VectorType &du) const
      {
        return checked_l2_norm(du)
                 <= parameters.update_tolerance * (1 + checked_l2_norm(u))
               || du.linfty_norm()
                    <= parameters.displacement_tolerance * length_scale;
      }

      bool
      energy_line_search(const double slope, double &alpha);

      bool
      quadratic_phase(const double slope, const double trial_energy);

      bool
      residual_line_search(double &alpha);

      bool
      retry_with_fresh_jacobian();

      bool
      take_step(const double alpha);
    };


    NewtonResult
    NewtonIteration::run()
    {
      try
        {
          timed_assemble(u, residual, need_jacobian);
        }
      catch (const SolverError &e)
        {
          result.failure = e.what();
          return result;
        }
      norm = checked_l2_norm(residual);
      result.residual_norms.push_back(norm);
      first_norm     = norm;
      current_energy = use_energy ? energy_at(u) : 0.;

      while (!finished_before_iteration() && solve_for_update())
        {
          double alpha = 1;
          if (!line_search(alpha))
            {
              if (retry_with_fresh_jacobian())
                continue;
              if (result.failure.empty())
                result.failure = "line search found no admissible step";
              return result;
            }
          if (take_step(alpha))
            return result;
        }
      return result;
    }


    /// The tests at the top of an iteration: whether Newton stops here,
    /// converged or not, before solving for another update.
    bool
    NewtonIteration::finished_before_iteration()
    {
      return stop_before_iteration(
        parameters, norm, first_norm, parameters.max_iterations, result);
    }


    /// The Newton update J du = -R; false (with the failure recorded) if
    /// the linear solver gives up.
    bool
    NewtonIteration::solve_for_update()
    {
      rhs.equ(-1., residual);
      const auto start = Clock::now();
      try
        {
          solve_jacobian(update, rhs, need_jacobian);
        }
      catch (const SolverError &e)
        {
          result.failure = e.what();
          return false;
        }
      result.solve_seconds += seconds_since(start);
      ++result.iterations;
      if (hooks)
        hooks->predict(update);
      return true;
    }


    /// Chooses the step length @p alpha along the update; leaves the
    /// accepted state in trial and its residual in trial_residual.
    /// Energy line search where the update descends (R.du < 0; R is the
    /// energy gradient); else the residual norm.
    bool
    NewtonIteration::line_search(double &alpha)
    {
      // An update that ends Newton when taken whole (take_step()'s update
      // tests) is taken whole: the line search could only shorten it, on
      // changes of the energy or the residual that are round-off by then
      // (a block held by stiff contact penalties and friction springs sat
      // at |R| = 1.3e-10, below what round-off lets the penalties reach,
      // with updates of 1e-16 that the line search cut to 0.01 until
      // Newton gave up).
      // It must leave a finite residual no more than twice the present
      // one (or the absolute tolerance): Newton then ends (take_step()),
      // so the energy is not needed.
      whole = false;
      if (ends_newton(update))
        {
          trial = u;
          trial.add(1., update);
          set_trial(1.);
          try
            {
              timed_assemble(trial, trial_residual, !reuse);
              const double trial_norm = checked_l2_norm(trial_residual);
              whole
                = std::isfinite(trial_norm)
                  && trial_norm
                       <= 2
                            * std::max(norm,
                                       parameters.absolute_residual_tolerance);
            }
          catch (const SolverError &)
            {
            }
          if (whole)
            return true;
        }
      const double slope
        = use_energy && std::isfinite(current_energy) ? residual * update : 0.;
      // Where even the full step's first-order decrease lies within the
      // energy's round-off (as energy_line_search() allows it), the energy
      // cannot judge a step length, but the residual norm can: a block
      // resting on a floor with friction (augmented Lagrangian) sat at
      // |R| = 3.1e-7 with updates of 1.2e-12, a first-order decrease of
      // 4e-19, every step length refused until Newton gave up.
      if (slope < 0 && -slope > energy_round_off * std::abs(current_energy))
        return energy_line_search(slope, alpha);
      return residual_line_search(alpha);
    }


    /// Armijo's sufficient decrease of the energy, step lengths from
    /// quadratic interpolation.
    bool
    NewtonIteration::energy_line_search(const double slope, double &alpha)
    {
      bool accepted = false;
      // Sums of many terms of either sign: allow their round-off.
      const double round_off    = energy_round_off * std::abs(current_energy);
      double       trial_energy = current_energy;
      bool         assembled    = false;
      for (unsigned int k = 0; k <= parameters.max_line_search_steps; ++k)
        {
          trial = u;
          trial.add(alpha, update);
          set_trial(alpha);
          trial_energy = energy_at(trial);
          if (trial_energy <= current_energy + 1e-4 * alpha * slope + round_off)
            {
              accepted = true;
              break;
            }
          if (k == 0 && std::isfinite(trial_energy)
              && quadratic_phase(slope, trial_energy))
            {
              current_energy = trial_energy;
              assembled      = true;
              accepted       = true;
              break;
            }
          // Minimizer of the quadratic through E(0), E'(0), E(alpha),
          // kept within [0.1, 0.5] alpha.
          double next = 0.5 * alpha;
          if (std::isfinite(trial_energy))
            {
              const double curvature
                = trial_energy - current_energy - slope * alpha;
              if (curvature > 0)
                next = -slope * alpha * alpha / (2 * curvature);
            }
          alpha = std::clamp(next, 0.1 * alpha, 0.5 * alpha);
        }
      if (!accepted && std::isfinite(trial_energy))
        accepted = true; // the last trial, as the residual search does
      if (accepted && !assembled)
        {
          try
            {
              timed_assemble(trial, trial_residual, !reuse);
              accepted       = std::isfinite(checked_l2_norm(trial_residual));
              current_energy = trial_energy;
            }
          catch (const SolverError &e)
            {
              result.failure = e.what();
              accepted       = false;
            }
        }
      return accepted;
    }


    /// Near a solution the energy's change falls below its round-off: a
    /// full step (in trial) that halves the residual is Newton's quadratic
    /// phase, take it, provided the energy did not rise by more than the
    /// first-order change (a saddle would). Assembles trial_residual.
    bool
    NewtonIteration::quadratic_phase(const double slope,
                                     const double trial_energy)
    {
      try
        {
          timed_assemble(trial, trial_residual, !reuse);
          const double trial_norm = checked_l2_norm(trial_residual);
          const double rise       = trial_energy - current_energy;
          return std::isfinite(trial_norm) && trial_norm < 0.5 * norm
                 && rise <= -slope
                              + 1e-8
                                  * std::max(std::abs(current_energy),
                                             std::abs(trial_energy));
        }
      catch (const SolverError &)
        {
          return false;
        }
    }


    /// Backtracking: accept the first step length that lowers |R| (or the
    /// full step when the line search is off; with NewtonHooks::full_steps
    /// the first that can be evaluated).
    bool
    NewtonIteration::residual_line_search(double &alpha)
    {
      for (unsigned int k = 0; k <= parameters.max_line_search_steps; ++k)
        {
          trial = u;
          trial.add(alpha, update);
          set_trial(alpha);
          try
            {
              // Without reuse the Jacobian is assembled with the trial
              // residual: the full step is almost always accepted, and
              // then it is the one the next iteration needs.
              timed_assemble(trial, trial_residual, !reuse);
              const double trial_norm = checked_l2_norm(trial_residual);
              if (std::isfinite(trial_norm)
                  && (trial_norm < norm || parameters.max_line_search_steps == 0
                      || k == parameters.max_line_search_steps
                      || (hooks && hooks->full_steps)))
                {
                  if (use_energy)
                    current_energy = energy_at(trial);
                  return true;
                }
            }
          catch (const SolverError &e)
            {
              result.failure = e.what();
            }
          alpha *= 0.5;
        }
      return false;
    }


    /// A kept Jacobian may be what made the line search fail: try once
    /// more with a fresh one from the same iterate. Whether to go on.
    bool
    NewtonIteration::retry_with_fresh_jacobian()
    {
      if (!reuse || need_jacobian)
        return false;
      need_jacobian = true;
      set_trial(0);
      try
        {
          timed_assemble(u, residual, true);
          result.failure.clear();
          return true;
        }
      catch (const SolverError &)
        {
          return false;
        }
    }


    /// Moves to the accepted trial state; returns whether Newton is done
    /// (converged by the update tests, or failed assembling a Jacobian).
    bool
    NewtonIteration::take_step(const double alpha)
    {
      result.failure.clear();
      u = trial;
      residual.swap(trial_residual);
      const double previous_norm = norm;
      norm                       = checked_l2_norm(residual);
      result.residual_norms.push_back(norm);
      // A kept Jacobian serves while it contracts at full steps.
      need_jacobian
        = !(reuse && alpha == 1 && std::isfinite(norm)
            && norm <= parameters.reuse_contraction * previous_norm);
      if (parameters.verbose)
        std::cout << "    Newton " << result.iterations << ": |R| = " << norm
                  << ", |du| = " << checked_l2_norm(update) << ", step "
                  << alpha << std::endl;

      if (alpha == 1 && (whole || ends_newton(update)))
        {
          result.converged = std::isfinite(norm);
          return true;
        }
      if (reuse && need_jacobian && !residual_converged())
        try
          {
            timed_assemble(u, residual, true);
          }
        catch (const SolverError &e)
          {
            result.failure = e.what();
            return true;
          }
      return false;
    }
  } // namespace


  double
  energy_or_infinity(const std::function<double(const VectorType &)> &energy,
                     const VectorType                                &x,
                     NewtonResult                                    &result)
  {
    const auto start = std::chrono::steady_clock::now();
    double     value = std::numeric_limits<double>::infinity();
    try
      {
        value = energy(x);
      }
    catch (const SolverError &)
      {
      }
    result.assembly_seconds += seconds_since(start);
    return std::isfinite(value) ? value
                                : std::numeric_limits<double>::infinity();
  }


  std::string
  no_convergence_message(const unsigned int max_iterations, const double norm)
  {
    // Three significant digits in any range (std::to_string prints a
    // small norm as 0.000000).
    std::ostringstream message;
    message << "no convergence in " << max_iterations
            << " iterations (residual norm " << std::setprecision(3) << norm
            << ", force units)";
    return message.str();
  }


  NewtonResult
  solve_newton(
    const NewtonParameters &parameters,
    VectorType             &u,
    const std::function<void(const VectorType &, VectorType &, bool)> &assemble,
    const std::function<void(VectorType &, const VectorType &, bool)>
                                                    &solve_jacobian,
    const std::function<double(const VectorType &)> &energy,
    const double                                     length_scale,
    const bool                                       jacobian_current,
    const NewtonHooks                               *hooks)
  {
    NewtonIteration iteration(parameters,
                              u,
                              assemble,
                              solve_jacobian,
                              energy,
                              length_scale,
                              jacobian_current,
                              hooks);
    return iteration.run();
  }
} // namespace tissuefem::solvers
