#include <tissuefem/base/input_error.h>
#include <tissuefem/base/timing.h>
#include <tissuefem/solvers/lbfgs.h>
#include <tissuefem/solvers/stopping.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <iostream>
#include <limits>

namespace tissuefem::solvers
{
  namespace
  {
    using Clock = std::chrono::steady_clock;

    /// One correction pair of the limited memory.
    struct Pair
    {
      VectorType s, y;
      double     rho;
    };

    /// -H R by the two-loop recursion over @p pairs (oldest first), H0
    /// applied by @p apply_h0.
    void
    direction(
      const std::deque<Pair>                                      &pairs,
      const VectorType                                            &R,
      const std::function<void(VectorType &, const VectorType &)> &apply_h0,
      VectorType                                                  &d)
    {
      VectorType          q(R);
      std::vector<double> a(pairs.size());
      q *= -1.;
      for (int i = static_cast<int>(pairs.size()) - 1; i >= 0; --i)
        {
          a[i] = pairs[i].rho * (pairs[i].s * q);
          q.add(-a[i], pairs[i].y);
        }
      apply_h0(d, q);
      for (unsigned int i = 0; i < pairs.size(); ++i)
        {
          const double b = pairs[i].rho * (pairs[i].y * d);
          d.add(a[i] - b, pairs[i].s);
        }
    }
  } // namespace


  NewtonResult
  solve_lbfgs(
    const NewtonParameters                                      &parameters,
    const unsigned int                                           memory,
    const unsigned int                                           max_iterations,
    VectorType                                                  &u,
    const std::function<void(const VectorType &, VectorType &)> &residual,
    const std::function<void(VectorType &, const VectorType &)> &apply_h0,
    const std::function<double(const VectorType &)>             &energy,
    const double                                                 length_scale)
  {
    NewtonResult result;
    VectorType   R(u), trial(u), trial_R(u), d(u);
    const auto   evaluate = [&](const VectorType &x, VectorType &r) {
      const auto start = Clock::now();
      residual(x, r);
      result.assembly_seconds += seconds_since(start);
      return r.l2_norm();
    };
    const auto h0 = [&](VectorType &z, const VectorType &q) {
      const auto start = Clock::now();
      apply_h0(z, q);
      result.solve_seconds += seconds_since(start);
    };
    double norm;
    try
      {
        norm = evaluate(u, R);
      }
    catch (const SolverError &e)
      {
        result.failure = e.what();
        return result;
      }
    result.residual_norms.push_back(norm);
    const double first_norm = norm;
    double       E          = energy_or_infinity(energy, u, result);
    if (!std::isfinite(E))
      {
        // No line search on the energy from here; the caller retries
        // with a fresh Hessian or a smaller step.
        result.failure = "the energy of the initial guess is not finite";
        return result;
      }
    std::deque<Pair> pairs;
    for (;;)
      {
        if (stop_before_iteration(
              parameters, norm, first_norm, max_iterations, result))
          return result;
        try
          {
            direction(pairs, R, h0, d);
            double slope = R * d;
            if (!(slope < 0) && !pairs.empty())
              {
                // The pairs' model is not positive definite here: start
                // again from H0.
                pairs.clear();
                direction(pairs, R, h0, d);
                slope = R * d;
              }
            if (!(slope < 0))
              {
                result.failure = "the kept Hessian gives no descent direction";
                return result;
              }
            ++result.iterations;
            // Armijo backtracking, quadratic interpolation within [0.1,
            // 0.5] of the last trial.
            const double round_off = energy_round_off * std::abs(E);
            double       alpha = 1, trial_E = E;
            bool         accepted = false;
            for (unsigned int k = 0; k <= parameters.max_line_search_steps; ++k)
              {
                trial = u;
                trial.add(alpha, d);
                trial_E = energy_or_infinity(energy, trial, result);
                if (trial_E <= E + 1e-4 * alpha * slope + round_off)
                  {
                    accepted = true;
                    break;
                  }
                double next = 0.5 * alpha;
                if (std::isfinite(trial_E))
                  {
                    const double curvature = trial_E - E - slope * alpha;
                    if (curvature > 0)
                      next = -slope * alpha * alpha / (2 * curvature);
                  }
                alpha = std::clamp(next, 0.1 * alpha, 0.5 * alpha);
              }
            if (!accepted)
              {
                result.failure = "line search found no admissible step";
                return result;
              }
            const double trial_norm = evaluate(trial, trial_R);
            Pair         pair{trial, trial_R, 0.};
            pair.s -= u;
            pair.y -= R;
            const double curvature = pair.y * pair.s;
            // A small full step says the iterate is near the solution only
            // where the residual contracts too (as Newton with a kept
            // Jacobian requires, 'Reuse contraction'): a poor Hessian
            // can make small steps far from it.
            const bool converged_by_update
              = alpha == 1 && trial_norm <= parameters.reuse_contraction * norm
                && (pair.s.l2_norm()
                      <= parameters.update_tolerance * (1 + trial.l2_norm())
                    || pair.s.linfty_norm()
                         <= parameters.displacement_tolerance * length_scale);
            u.swap(trial);
            R.swap(trial_R);
            norm = trial_norm;
            E    = trial_E;
            result.residual_norms.push_back(norm);
            if (parameters.verbose)
              std::cout << "    L-BFGS " << result.iterations
                        << ": |R| = " << norm << ", step " << alpha
                        << std::endl;
            if (converged_by_update && std::isfinite(norm))
              {
                result.converged = true;
                return result;
              }
            // Only pairs of positive curvature keep the inverse Hessian
            // positive definite (Nocedal and Wright, sec 6.1).
            if (curvature > 1e-12 * pair.s.l2_norm() * pair.y.l2_norm())
              {
                pair.rho = 1. / curvature;
                pairs.push_back(std::move(pair));
                if (pairs.size() > memory)
                  pairs.pop_front();
              }
          }
        catch (const SolverError &e)
          {
            result.failure = e.what();
            return result;
          }
      }
  }
} // namespace tissuefem::solvers
