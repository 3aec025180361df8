#pragma once

#include <tissuefem/base/parallel.h>
#include <tissuefem/solvers/newton.h>

#include <functional>

namespace tissuefem::solvers
{
  /**
   * Limited-memory BFGS on an energy E whose gradient is the residual R
   * (Nocedal and Wright 2006, algorithms 7.4 and 7.5), with a fixed
   * initial inverse Hessian: @p apply_h0(z, q) solves H0 z = q with a
   * matrix factorized once and kept (Liu, Bouaziz and Kavan 2017 keep a
   * prefactored Laplacian-like matrix; here it is a Jacobian c M + K of
   * an earlier state, which the caller refreshes when it serves badly).
   * An iteration costs one residual, one energy per line-search trial, one
   * solve with the kept factorization and 4 @p memory vector updates,
   * instead of Newton's assembly and factorization of the Jacobian.
   *
   * Directions come from the two-loop recursion over the last @p memory
   * pairs (s, y) with y . s > 0; a direction that does not descend drops
   * the pairs and takes -H0^{-1} R. Step lengths satisfy Armijo's
   * sufficient decrease of E (quadratic interpolation between trials, at
   * most 'Maximum line search steps' of @p parameters); the energy may be
   * infinite (an inverted element) and the trial is then shortened.
   * Converged by Newton's tests of @p parameters: |R| <= absolute
   * tolerance, or |R| <= relative tolerance times the first |R|, or, after
   * a full step s that contracted |R| by 'Reuse contraction' at least,
   * |s| <= update tolerance (1 + |u|) or max |s| <= displacement tolerance
   * times @p length_scale. Fails at once where the energy of @p u is not
   * finite. At most
   * @p max_iterations iterations. The result's iterations are L-BFGS
   * iterations, its jacobians 0.
   */
  NewtonResult
  solve_lbfgs(
    const NewtonParameters                                      &parameters,
    const unsigned int                                           memory,
    const unsigned int                                           max_iterations,
    VectorType                                                  &u,
    const std::function<void(const VectorType &, VectorType &)> &residual,
    const std::function<void(VectorType &, const VectorType &)> &apply_h0,
    const std::function<double(const VectorType &)>             &energy,
    const double                                                 length_scale);
} // namespace tissuefem::solvers
