#pragma once

#include <tissuefem/solvers/newton.h>

#include <cmath>

namespace tissuefem::solvers
{
  /**
   * The round-off of an energy of size |E|, relative: energies are sums of
   * many terms of either sign over the cells, so two evaluations of
   * nearby states differ by about 1e-11 |E| with no decrease behind it.
   * Changes within this are not judged as decrease or increase (Newton's
   * line searches and slope test, the trust region, L-BFGS).
   */
  constexpr double energy_round_off = 1e-11;

  /**
   * The tests every nonlinear solver (Newton's globalizations, L-BFGS)
   * makes before an iteration, with the residual norm @p norm of the
   * current iterate and @p first_norm of the first: a non-finite residual
   * fails; |R| <= 'Absolute residual tolerance', or (after the first
   * iteration) |R| <= 'Relative residual tolerance' |R_0|, converges;
   * @p max_iterations reached fails. Returns whether to stop, with
   * @p result's converged or failure set.
   */
  inline bool
  stop_before_iteration(const NewtonParameters &parameters,
                        const double            norm,
                        const double            first_norm,
                        const unsigned int      max_iterations,
                        NewtonResult           &result)
  {
    if (!std::isfinite(norm))
      {
        result.failure = "residual is not finite";
        return true;
      }
    if (norm <= parameters.absolute_residual_tolerance
        || (result.iterations > 0
            && norm <= parameters.relative_residual_tolerance * first_norm))
      {
        result.converged = true;
        return true;
      }
    if (result.iterations >= max_iterations)
      {
        result.failure = no_convergence_message(max_iterations, norm);
        return true;
      }
    return false;
  }
} // namespace tissuefem::solvers
