#pragma once

#include <tissuefem/solvers/newton.h>

#include <functional>

namespace tissuefem::solvers
{
  /**
   * Newton's method globalized by a trust region on the energy ('Newton
   * solver/Globalization = trust region'): Powell's dogleg between the
   * Cauchy point and the Newton step (Nocedal and Wright 2006, sec 4.1),
   * with the step of each iteration bounded by a radius Delta in the l2
   * norm of the update (length units). The model is
   *
   *   m(p) = E(u) + R.p + 1/2 p.J p,
   *
   * R the residual (the energy's gradient), J the Jacobian. A trial u + p
   * is accepted when the energy falls by at least 1e-4 of what the model
   * predicts; Delta shrinks to a quarter of |p| where the ratio of actual
   * to predicted decrease is below 1/4 and doubles where it is above 3/4
   * at the boundary. Where J is indefinite (a buckling leg, a snap-through)
   * the Newton step may climb: then the dogleg follows the steepest
   * descent -R to the boundary, along which the model has negative
   * curvature, instead of letting a line search on the residual norm
   * wander between basins, which is what the energy line search falls
   * back to there.
   *
   * The same arguments as solve_newton(), plus @p jacobian_vmult(Jv, v)
   * with the last assembled Jacobian, and the tests for convergence are
   * the same. Every iteration assembles and factorizes a new Jacobian:
   * the ratio test needs a model of the current iterate.
   */
  NewtonResult
  solve_trust_region(
    const NewtonParameters &parameters,
    VectorType             &u,
    const std::function<void(const VectorType &, VectorType &, bool)> &assemble,
    const std::function<void(VectorType &, const VectorType &, bool)>
                                                                &solve_jacobian,
    const std::function<void(VectorType &, const VectorType &)> &jacobian_vmult,
    const std::function<double(const VectorType &)>             &energy,
    const double                                                 length_scale);
} // namespace tissuefem::solvers
