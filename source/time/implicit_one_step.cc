#include <tissuefem/base/input_error.h>
#include <tissuefem/base/timing.h>
#include <tissuefem/solvers/trust_region.h>
#include <tissuefem/time/implicit_one_step.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>

namespace tissuefem::time
{
  namespace
  {
    /// Ends a step's iteration unknowns (solid::IterationUnknowns) when
    /// told, or else when it goes out of scope.
    struct EndIterations
    {
      solid::IterationUnknowns *unknowns;

      void
      end(const bool converged)
      {
        if (unknowns)
          unknowns->end_iterations(converged);
        unknowns = nullptr;
      }

      ~EndIterations()
      {
        end(false);
      }
    };
  } // namespace


  void
  ImplicitOneStep::initialize(Context &c, State &state)
  {
    context   = &c;
    step_size = c.time.time_step;
    c.solid.initialize_vector(state.a);
    // Only the trust region multiplies with the Jacobian itself.
    c.solid.solve_only_through_operators(!c.newton.trust_region,
                                         c.linear_solver);
  }


  double
  ImplicitOneStep::lift_boundary_increment(const double mass_coefficient,
                                           const double time,
                                           VectorType  &u,
                                           StepReport  &report,
                                           const bool   refactorize,
                                           const bool   jacobian_needed)
  {
    auto      &solid = context->solid;
    VectorType residual, update;
    auto       start = std::chrono::steady_clock::now();
    const bool assembled
      = solid.implicit_residual_lifting(u,
                                        u_tilde,
                                        mass_coefficient,
                                        time,
                                        residual,
                                        jacobian_needed || refactorize);
    if (deferred_shift != 0)
      {
        // r(u_n) = R(u_n) - c' M (u_n - u_tilde') on the free rows (the
        // prescribed rows are zero: their values do not change).
        VectorType difference(u);
        difference -= u_tilde;
        shift.reinit(u);
        solid.mass_vmult(shift, difference);
        shift.sadd(-mass_coefficient, 1., residual);
        solid.zero_constrained_entries(shift);
        shift *= deferred_shift;
        deferred_shift = 0;
      }
    if (damped)
      residual += shift;
    report.assembly_seconds += seconds_since(start);
    if (assembled)
      ++report.jacobian_evaluations;
    residual *= -1.;
    update.reinit(u);
    const bool from_guess
      = !context->linear_solver.direct() && update_guess(u, update);
    start = std::chrono::steady_clock::now();
    solid.solve_jacobian(
      context->linear_solver, update, residual, refactorize, 0., from_guess);
    report.solve_seconds += seconds_since(start);
    // The cell unknowns of the three-field element move with the update.
    auto *unknowns = solid.iteration_unknowns();
    if (unknowns && unknowns->iterating())
      {
        unknowns->predict_update(update);
        unknowns->set_step_length(1);
      }
    u += update;
    ++report.newton_iterations;
    return update.linfty_norm();
  }


  double
  ImplicitOneStep::keep_better_guess(const VectorType &guess,
                                     const double      mass_coefficient,
                                     const double      time,
                                     VectorType       &lifted,
                                     const double      motion)
  {
    // The lifting is a full Newton step without a line search: where the
    // load increment is nonlinear (a nearly incompressible body under a
    // traction step) it can overshoot, and Newton then starts farther
    // away than from the guess. Keep the lifted state only if its energy
    // is not above that of the guess with the new boundary values written
    // in (infinite where that distorts elements into inversion).
    auto      &solid = context->solid;
    VectorType plain(guess);
    solid.apply_dirichlet_values(time, plain);
    const double lifted_energy = energy(lifted, mass_coefficient, time);
    const double plain_energy  = energy(plain, mass_coefficient, time);
    if (lifted_energy <= plain_energy || !std::isfinite(plain_energy))
      return motion;
    // The Jacobian was assembled at the guess: still current if the
    // boundary values did not move.
    VectorType change(plain);
    change -= guess;
    lifted = plain;
    return change.linfty_norm() == 0 ? 0. : -1.;
  }


  double
  ImplicitOneStep::lift(const double              c,
                        const double              t_start,
                        const double              t_new,
                        VectorType               &u,
                        StepReport               &report,
                        solid::IterationUnknowns *unknowns)
  {
    // The lifting's Jacobian, factorized at the guess, serves Newton's
    // first iterations ('Jacobian reuse') when the lifting moved the body
    // little (below 1 % of its size: a smooth step). After a larger motion
    // (a crushed body springing back) it may lead modified Newton to
    // another equilibrium (measured: tests/unit/inversion_recovery_*), so
    // Newton starts with a fresh Jacobian there.
    double     motion = -1;
    VectorType guess;
    if (context->newton.lift_boundary_increments)
      try
        {
          // The guess is kept for keep_better_guess() below.
          const bool compare = c == 0 && unknowns == nullptr;
          if (compare)
            guess = u;
          // With 'Jacobian reuse across steps', the factorization of an
          // earlier step of the same size serves while the steps converge
          // (Newton makes a fresh one where it contracts too slowly).
          const bool refactorize
            = !(context->newton.reuse_jacobian
                && context->newton.reuse_across_steps && kept_coefficient == c);
          motion = lift_boundary_increment(c, t_new, u, report, refactorize);
          kept_coefficient = c;
          // Only without inertia: there the load increment meets the
          // bare stiffness; with a mass term (real-time dynamic scenes)
          // the lifting is well conditioned and the check would cost two
          // energy evaluations a step. Not with the three-field update,
          // whose lifted state is off the constraint (its energy no
          // measure) and whose lifting does not overshoot so (Cook's
          // membrane: 4-5 iterations per step without the check).
          if (compare)
            motion = keep_better_guess(guess, c, t_new, u, motion);
        }
      catch (const SolverError &)
        {
          // A guess the model cannot evaluate (inverted elements), or a
          // singular Jacobian: Newton starts from the guess with the new
          // boundary values written in, and may halve the step.
          kept_coefficient = -1;
          if (unknowns)
            unknowns->begin_iterations(t_start);
        }
    return motion;
  }


  std::string
  ImplicitOneStep::attempt(const State &state,
                           const double h,
                           State       &next,
                           StepReport  &report)
  {
    auto        &solid = context->solid;
    const double t_new = state.time + h;
    const double c     = begin_attempt(state, h, next);
    // The formulation's own unknowns (the three-field element's cell
    // dilatations and pressures, 'Materials/Mean dilatation/Update'):
    // Newton updates them with u within this step.
    solid::IterationUnknowns *unknowns = solid.iteration_unknowns();
    if (unknowns)
      unknowns->begin_iterations(state.time);
    // Ended after Newton, or however the attempt ends, so that no other
    // assembly sees them.
    EndIterations iterations{unknowns};
    const double  motion = lift(c, state.time, t_new, next.u, report, unknowns);
    const bool    lifted = motion >= 0 && motion <= 0.01 * solid.length_scale();
    solid.apply_dirichlet_values(t_new, next.u);
    // The three-field iterates lie off the constraint theta(u) = theta~
    // until convergence, where the energy is no merit, and the residual
    // norm refuses the right steps of the stiff problem (measured: Cook's
    // membrane without the boundary lifting took 159 step halvings with
    // a residual-norm line search, 4 iterations per step with full
    // steps). So Newton takes full steps, as deal.II's step-44 does,
    // shortened only where a trial cannot be evaluated.
    solvers::NewtonHooks hooks;
    if (unknowns)
      {
        hooks.full_steps = true;
        hooks.predict
          = [unknowns](const VectorType &du) { unknowns->predict_update(du); };
        hooks.trial = [unknowns](const double alpha) {
          unknowns->set_step_length(alpha);
        };
      }
    std::function<double(const VectorType &)> step_energy;
    if (!unknowns)
      step_energy = [&](const VectorType &x) { return energy(x, c, t_new); };
    const auto step_residual = [&](const VectorType &x, VectorType &r, bool J) {
      residual(x, c, t_new, r, J);
    };
    const auto solve = [&, first = 0.](VectorType       &x,
                                       const VectorType &b,
                                       const bool        refactorize) mutable {
      // Inexact Newton (Eisenstat and Walker 1996) for iterative solvers:
      // |J du + R_k| <= eta_k |R_k|, eta_k = min(0.1, 0.5 |R_k| / |R_0|),
      // tight only where Newton's own residual is small.
      const double norm = b.l2_norm();
      if (first == 0)
        first = norm;
      solid.solve_jacobian(context->linear_solver,
                           x,
                           b,
                           refactorize,
                           std::min(0.1, 0.5 * norm / first));
    };
    const auto newton = [&](const bool lifted_first) {
      return context->newton.trust_region && step_energy
               ? solvers::solve_trust_region(
                 context->newton,
                 next.u,
                 step_residual,
                 solve,
                 [&](VectorType &Jv, const VectorType &v) {
                   solid.jacobian().vmult(Jv, v);
                 },
                 step_energy,
                 solid.length_scale())
               : solvers::solve_newton(context->newton,
                                       next.u,
                                       step_residual,
                                       solve,
                                       step_energy,
                                       solid.length_scale(),
                                       lifted_first,
                                       unknowns ? &hooks : nullptr);
    };
    solvers::NewtonResult result = newton(lifted);
    const auto            count  = [&](const solvers::NewtonResult &r) {
      report.jacobian_evaluations += r.jacobians;
      report.newton_iterations += r.iterations;
      report.assembly_seconds += r.assembly_seconds;
      report.solve_seconds += r.solve_seconds;
    };
    count(result);
    // The step controller weighs the first solve, which the step size
    // decides (the re-solves take the multipliers' small corrections).
    last_iterations = result.iterations;
    // The factorization kept for the next step's lifting: this step's
    // (the lifting's, or Newton's last fresh one), if the step converged.
    if (!result.converged || motion < 0)
      kept_coefficient = -1;
    else if (result.jacobians > 0)
      kept_coefficient = c;
    // Multipliers (an augmented-Lagrangian contact): solved again from
    // the converged state, with a fresh Jacobian, until they settle.
    for (unsigned int update = 0; result.converged; ++update)
      {
        std::string why;
        const auto  status = solid.augment(next.u, t_new, update, why);
        if (status == solid::Augmentation::satisfied)
          break;
        if (status == solid::Augmentation::failed)
          return why;
        result = newton(false);
        count(result);
        ++report.multiplier_updates;
        kept_coefficient = -1;
      }
    iterations.end(result.converged);
    if (!result.converged)
      return result.failure.empty() ? std::string("no convergence")
                                    : result.failure;
    report.residual_norm = result.residual_norms.back();
    next.time            = t_new;
    // Newton leaves constrained entries alone; set hanging nodes (and the
    // prescribed values, unchanged) in the state.
    solid.apply_dirichlet_values(t_new, next.u);
    finish(state, rates_u_tilde(), h, next);
    return {};
  }


  double
  ImplicitOneStep::begin_attempt(const State &state,
                                 const double h,
                                 State       &next)
  {
    auto &solid = context->solid;
    if (next.u.size() != state.u.size())
      solid.initialize_vector(next.u);
    predict(state, h, u_tilde, next.u);
    solid.begin_step(state.u, state.time);
    return damp(state, h, mass_coefficient(h), state.time + h);
  }


  void
  ImplicitOneStep::backward_euler_prediction(const State &old_state,
                                             const double h,
                                             VectorType  &u_tilde,
                                             VectorType  &initial_guess) const
  {
    u_tilde = old_state.u;
    u_tilde.add(h, old_state.v);
    initial_guess = u_tilde;
    if (context->time.extrapolate)
      initial_guess.add(h * h, old_state.a);
  }


  double
  ImplicitOneStep::damp(const State &old_state,
                        const double h,
                        const double c,
                        const double t_new,
                        const bool   from_lifting)
  {
    deferred_shift     = 0;
    const double alpha = context->time.rayleigh_mass;
    const double beta  = context->time.rayleigh_stiffness;
    damped = capabilities().rayleigh_damping && (alpha > 0 || beta > 0);
    if (!damped)
      return c;
    undamped_u_tilde         = u_tilde;
    const double c_with_mass = c + alpha / h;
    // u_tilde' = (c u_tilde + alpha/h u_n) / (c + alpha/h)
    u_tilde.sadd(c / c_with_mass, alpha / h / c_with_mass, old_state.u);
    // g = -beta/(h kappa) r(u_n), kappa = 1 + beta/h.
    const double shift_factor = -beta / (h + beta);
    if (beta > 0 && from_lifting)
      deferred_shift = shift_factor;
    else if (beta > 0)
      {
        // r(u_n) at t_{n+1}: the solid's residual without the mass term.
        context->solid.implicit_residual(
          old_state.u, u_tilde, 0., t_new, shift, false);
        shift *= shift_factor;
      }
    else
      shift.reinit(old_state.u);
    return damped_coefficient(c, h);
  }


  double
  ImplicitOneStep::damped_coefficient(const double c, const double h) const
  {
    // c' = (c + alpha/h) / kappa
    return (c + context->time.rayleigh_mass / h)
           / (1 + context->time.rayleigh_stiffness / h);
  }


  double
  ImplicitOneStep::damping_work(const State &old_state,
                                const State &new_state,
                                const double h)
  {
    if (!damped)
      return 0;
    const double c        = mass_coefficient(h);
    const double c_damped = damped_coefficient(c, h);
    // The step's equation with the damping force f_d written out,
    // c M (u - u_tilde) + f_d + r(u) = 0, and the solved one divided by
    // kappa, c' M (u - u_tilde') + r(u) + g = 0, give on the free rows
    // f_d = g + M (c' (u - u_tilde') - c (u - u_tilde)).
    VectorType combination(new_state.u), force, step(new_state.u);
    combination.sadd(c_damped - c, -c_damped, u_tilde);
    combination.add(c, undamped_u_tilde);
    context->solid.initialize_vector(force);
    context->solid.mass_vmult(force, combination);
    force += shift;
    context->solid.zero_constrained_entries(force);
    step -= old_state.u;
    return force * step;
  }


  void
  ImplicitOneStep::residual(const VectorType &u,
                            const double      c,
                            const double      time,
                            VectorType       &r,
                            const bool        with_jacobian)
  {
    context->solid.implicit_residual(u, u_tilde, c, time, r, with_jacobian);
    if (damped)
      r += shift;
  }


  double
  ImplicitOneStep::energy(const VectorType &u,
                          const double      c,
                          const double      time)
  {
    const double e = context->solid.implicit_energy(u, u_tilde, c, time);
    return damped ? e + shift * u : e;
  }


  StepReport
  ImplicitOneStep::advance(State &state, const double end_time)
  {
    auto      &linear_solver = context->linear_solver;
    StepReport report;
    double     h   = std::min(step_size, end_time - state.time);
    requested_step = h;
    State              next;
    const unsigned int linear_before = linear_solver.statistics().iterations;
    bool               reduced       = false;
    for (unsigned int halvings = 0;; ++halvings)
      {
        const std::string failure = attempt(state, h, next, report);
        if (failure.empty())
          break;
        ++report.rejected_attempts;
        failed_step = h;
        reduced     = true;
        std::ostringstream message;
        message << "Newton failed at t = " << state.time + h
                << " with dt = " << h << ": " << failure;
        if (const std::string why = halving_cannot_help(state); !why.empty())
          throw SolverError(message.str() + "; " + why);
        // The smallest step 'Maximum step halvings' allows, whichever
        // way the step got there: successful steps after failures grow
        // only geometrically back towards a failed size, so near a limit
        // point a run could otherwise creep on in steps below the
        // resolution of t itself (measured: dt = 1e-17, t unchanged, for
        // ever).
        const double smallest
          = context->time.time_step
            / std::ldexp(1., context->time.max_step_halvings);
        if (halvings == context->time.max_step_halvings || h / 2 < smallest)
          {
            std::ostringstream smallest_text;
            smallest_text << smallest;
            throw SolverError(
              message.str() + "; gave up after " + std::to_string(halvings)
              + " step halvings of this step, at the smallest step 'Time "
                "integration/Maximum step halvings' allows ('Time step' / 2^"
              + std::to_string(context->time.max_step_halvings) + " = "
              + smallest_text.str() + ")" + last_equilibrium(state));
          }
        parallel_tools::screen()
          << "  " << message.str() << "; retrying with dt = " << h / 2
          << std::endl;
        h /= 2;
      }
    // Newton and linear iterations of all attempts, failed ones included:
    // they are what the step cost.
    report.linear_iterations
      = linear_solver.statistics().iterations - linear_before;
    // Contributions with history (friction's stick points) commit only
    // now: an attempt that failed never got here.
    context->solid.accept_step(next.u, next.time);
    report.damping_work += damping_work(state, next, h);
    state.time = next.time;
    state.u.swap(next.u);
    state.v.swap(next.v);
    state.a.swap(next.a);
    if (damped)
      {
        state.damping.alpha = context->time.rayleigh_mass;
        state.damping.beta  = context->time.rayleigh_stiffness;
        state.damping.step  = h;
        state.damping.u_old = next.u; // u_n, swapped out above
      }
    else
      state.damping = solid::RayleighDamping();
    report.dt = h;
    step_size = next_step_size(h, reduced);
    return report;
  }


  void
  ImplicitOneStep::backward_difference_rates(const State      &old_state,
                                             const VectorType &u_tilde,
                                             const double      h,
                                             State            &new_state)
  {
    new_state.v = new_state.u;
    new_state.v -= old_state.u;
    new_state.v /= h;
    new_state.a = new_state.u;
    new_state.a -= u_tilde;
    new_state.a /= h * h;
  }


  double
  ImplicitOneStep::next_step_size(const double h, const bool reduced)
  {
    const unsigned int optimal = context->time.optimal_iterations;
    // A step shortened only to land on an output time says nothing about
    // the step size: grow from the size asked for.
    const double base = reduced ? h : std::max(h, step_size);
    double       next = 2 * base;
    if (optimal > 0)
      next = base
             * std::clamp(std::sqrt(double(optimal)
                                    / std::max(1u, last_iterations)),
                          0.5,
                          2.);
    // Memory of the last failure: approach it geometrically, never jump
    // back to it; it fades as steps succeed.
    if (next >= failed_step)
      next = std::min(next, std::sqrt(h * failed_step));
    failed_step *= 1.25;
    return std::min(context->time.time_step, next);
  }
} // namespace tissuefem::time
