#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/base/timing.h>
#include <tissuefem/solvers/stopping.h>
#include <tissuefem/solvers/trust_region.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>

namespace tissuefem::solvers
{
  namespace
  {
    using Clock = std::chrono::steady_clock;

    /// The dogleg step of radius @p radius from the Newton step @p newton
    /// (usable: a descent direction of positive curvature) and the
    /// gradient @p g with curvature gJg = g.J g, into @p step. Returns
    /// whether the step is the whole Newton step.
    bool
    dogleg(const VectorType &g,
           const double      gJg,
           const VectorType &newton,
           const bool        newton_usable,
           const double      radius,
           VectorType       &step)
    {
      const double newton_norm = newton.l2_norm();
      if (newton_usable && newton_norm <= radius)
        {
          step = newton;
          return true;
        }
      const double gg     = g * g;
      const double g_norm = std::sqrt(gg);
      // The model's minimizer along -g (Cauchy point), or the boundary
      // where the curvature along -g is not positive.
      const double tau
        = gJg > 0 ? std::min(gg / gJg, radius / g_norm) : radius / g_norm;
      step.equ(-tau, g);
      if (!newton_usable || tau * g_norm >= radius)
        return false;
      // From the Cauchy point towards the Newton step, to the boundary:
      // |c + s (n - c)| = radius, s in [0, 1].
      VectorType d(newton);
      d -= step;
      const double a = d * d, b = 2 * (step * d),
                   c = step * step - radius * radius;
      const double s
        = (-b + std::sqrt(std::max(0., b * b - 4 * a * c))) / (2 * a);
      step.add(std::clamp(s, 0., 1.), d);
      return false;
    }
  } // namespace


  NewtonResult
  solve_trust_region(
    const NewtonParameters &parameters,
    VectorType             &u,
    const std::function<void(const VectorType &, VectorType &, bool)> &assemble,
    const std::function<void(VectorType &, const VectorType &, bool)>
                                                                &solve_jacobian,
    const std::function<void(VectorType &, const VectorType &)> &jacobian_vmult,
    const std::function<double(const VectorType &)>             &energy,
    const double                                                 length_scale)
  {
    NewtonResult result;
    VectorType   residual(u), newton(u), step(u), trial(u), trial_residual(u),
      product(u), rhs(u);
    const auto timed_assemble = [&](const VectorType &x, VectorType &r) {
      const auto start = Clock::now();
      assemble(x, r, true);
      result.assembly_seconds += seconds_since(start);
      ++result.jacobians;
    };
    // +infinity where the model cannot evaluate a state: the region
    // shrinks.
    const auto energy_at = [&](const VectorType &x) {
      return energy_or_infinity(energy, x, result);
    };

    try
      {
        timed_assemble(u, residual);
      }
    catch (const SolverError &e)
      {
        result.failure = e.what();
        return result;
      }
    double norm = checked_l2_norm(residual);
    result.residual_norms.push_back(norm);
    const double first_norm     = norm;
    double       current_energy = energy_at(u);
    double       radius         = 0;
    // Below this the region has collapsed: no step lowers the energy.
    const double smallest_radius
      = 1e-14 * std::max(length_scale, 1e-300) + 1e-300;

    while (true)
      {
        if (stop_before_iteration(
              parameters, norm, first_norm, parameters.max_iterations, result))
          return result;

        // The Newton step and the curvatures of the model.
        rhs.equ(-1., residual);
        bool       newton_usable = true;
        const auto start         = Clock::now();
        try
          {
            solve_jacobian(newton, rhs, true);
          }
        catch (const SolverError &)
          {
            // A singular Jacobian: the steepest descent still serves.
            newton        = 0;
            newton_usable = false;
          }
        result.solve_seconds += seconds_since(start);
        ++result.iterations;
        jacobian_vmult(product, residual);
        const double gJg = residual * product;
        jacobian_vmult(product, newton);
        newton_usable = newton_usable && all_finite(newton)
                        && residual * newton < 0 && newton * product > 0;
        if (radius == 0)
          radius = newton_usable ? newton.l2_norm() : 0.1 * length_scale;

        // Shrink the region until a step lowers the energy as the model
        // predicts (at least a 1e-4 share of it).
        bool accepted = false, whole_newton = false;
        while (!accepted)
          {
            if (radius < smallest_radius)
              {
                result.failure = "trust region collapsed (no step lowers "
                                 "the energy)";
                return result;
              }
            whole_newton
              = dogleg(residual, gJg, newton, newton_usable, radius, step);
            jacobian_vmult(product, step);
            const double predicted
              = -(residual * step + 0.5 * (step * product));
            trial = u;
            trial += step;
            const double trial_energy = energy_at(trial);
            const double actual       = current_energy - trial_energy;
            const double step_norm    = step.l2_norm();
            // Near a solution the energy's change falls below its
            // round-off: there a Newton step that halves the residual is
            // taken (Newton's quadratic phase).
            const double round_off
              = energy_round_off * std::abs(current_energy);
            if (std::isfinite(trial_energy) && whole_newton
                && std::abs(predicted) <= round_off)
              {
                try
                  {
                    timed_assemble(trial, trial_residual);
                    accepted = checked_l2_norm(trial_residual) < 0.5 * norm;
                  }
                catch (const SolverError &)
                  {
                  }
                if (accepted)
                  current_energy = trial_energy;
                else
                  {
                    // The Jacobian kept is the trial's now: assemble at u.
                    timed_assemble(u, residual);
                    radius = 0.25 * step_norm;
                  }
                continue;
              }
            const double ratio = actual / predicted;
            if (!std::isfinite(trial_energy) || !(predicted > 0)
                || ratio < 0.25)
              radius = 0.25 * step_norm;
            else if (ratio > 0.75 && step_norm >= 0.99 * radius)
              radius = 2 * radius;
            if (std::isfinite(trial_energy) && predicted > 0 && ratio >= 1e-4)
              {
                try
                  {
                    timed_assemble(trial, trial_residual);
                    accepted = true;
                  }
                catch (const SolverError &)
                  {
                    radius = 0.25 * step_norm;
                    timed_assemble(u, residual);
                  }
              }
            if (accepted)
              current_energy = trial_energy;
          }

        u = trial;
        residual.swap(trial_residual);
        norm = checked_l2_norm(residual);
        result.residual_norms.push_back(norm);
        if (parameters.verbose)
          std::cout << "    trust region " << result.iterations
                    << ": |R| = " << norm << ", |du| = " << step.l2_norm()
                    << ", radius " << radius
                    << (whole_newton ? " (Newton step)" : " (dogleg)")
                    << std::endl;
        if (whole_newton
            && (step.l2_norm()
                  <= parameters.update_tolerance * (1 + u.l2_norm())
                || step.linfty_norm()
                     <= parameters.displacement_tolerance * length_scale))
          {
            result.converged = std::isfinite(norm);
            return result;
          }
      }
  }
} // namespace tissuefem::solvers
