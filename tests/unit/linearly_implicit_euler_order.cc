// The linearly implicit Euler integrator (one linear solve per step) on the
// single degree of freedom of the order tests: a 1D bar (0, 1) of one linear
// element clamped at x = 0, E = 1, nu = 0, rho = 1, consistent mass, so the
// free node obeys (1/3) u'' + P(1 + u) = 0.
//
// 1. Linear elastic (P(F) = F - 1), started from u = 0.01 at rest:
//    u(t) = 0.01 cos(sqrt(3) t). The errors at t = 1 for steps 0.02, 0.01,
//    0.005 must fall with observed order 1 (within 0.2).
// 2. Neo-Hookean (lambda = 0, mu = 1/2, P(F) = mu (F - 1/F)), started from
//    u = 0.5 (F = 1.5) at rest, a strongly nonlinear oscillation between F =
//    1.5 and about 0.58. The reference at t = 0.6 (mid-swing) is this scalar
//    ODE integrated here by the classical Runge-Kutta method with 1e-4 steps
//    (error ~ 1e-14), independent of tissuefem's integrators. The errors for
//    steps 0.01, 0.005, 0.0025 must fall with observed order 1 within 0.2;
//    and the linearly implicit answer must differ from backward Euler
//    converged to Newton's tolerance (1e-10) by more than 1e-8, so the
//    test sees the linearization and not a hidden Newton loop.
// 3. The same with 'Factorization interval = 8' (a W-method: the solve uses
//    the factorization of up to 7 steps before): still order 1 within 0.2,
//    and an answer that differs from the method with fresh factorizations
//    (so the kept ones are really used).

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/app/parameters.h>

#include "../tests.h"
#include "solid_scene.h"

#include <cmath>
#include <iostream>
#include <sstream>

using namespace dealii;
using namespace tissuefem;

namespace
{
  const std::string scene = tissuefem_tests::one_element_bar(R"(
      set Integrator = linearly implicit Euler
)");

  /// The free node's displacement at t = 1 of (1/3) u'' = -mu (F - 1/F), F
  /// = 1 + u, u(0) = u0, u'(0) = 0, by RK4 with steps 1e-4.
  double
  neo_hookean_reference(const double u0, const double end_time)
  {
    const double mu    = 0.5;
    auto         accel = [&](const double u) {
      const double F = 1 + u;
      return -3. * mu * (F - 1. / F);
    };
    double             u = u0, v = 0;
    const unsigned int steps = std::lround(end_time / 1e-4);
    const double       h     = end_time / steps;
    for (unsigned int n = 0; n < steps; ++n)
      {
        const double k1u = v, k1v = accel(u);
        const double k2u = v + h / 2 * k1v, k2v = accel(u + h / 2 * k1u);
        const double k3u = v + h / 2 * k2v, k3v = accel(u + h / 2 * k2u);
        const double k4u = v + h * k3v, k4v = accel(u + h * k3u);
        u += h / 6 * (k1u + 2 * k2u + 2 * k3u + k4u);
        v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
      }
    return u;
  }

  /// The free node's displacement at t = 1 with step @p step.
  double
  final_displacement(ParameterHandler &prm,
                     const double      step,
                     const double      end_time = 1.)
  {
    Vector<double> u;
    tissuefem_tests::run_to_end<1>(prm, step, end_time, &u);
    double sum = 0; // the clamped node's entry is 0
    for (const double value : u)
      sum += value;
    return sum;
  }

  void
  check_order(const std::vector<double> &errors, const std::string &name)
  {
    const double order_1 = std::log2(errors[0] / errors[1]);
    const double order_2 = std::log2(errors[1] / errors[2]);
    tissuefem_tests::check(std::abs(order_1 - 1.) < 0.2
                             && std::abs(order_2 - 1.) < 0.2,
                           name + ": observed order 1 within 0.2",
                           "orders " + std::to_string(order_1) + ", "
                             + std::to_string(order_2));
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ParameterHandler                 prm;
  declare_all_parameters(prm);
  prm.parse_input_from_string(scene);
  std::ostringstream discarded;
  std::streambuf    *screen = std::cout.rdbuf(discarded.rdbuf());

  std::vector<double> linear_errors;
  const double        exact = 0.01 * std::cos(std::sqrt(3.));
  for (const double step : {0.02, 0.01, 0.005})
    linear_errors.push_back(std::abs(final_displacement(prm, step) - exact));

  prm.enter_subsection("Materials");
  prm.set("Model", "neo-Hookean");
  prm.leave_subsection();
  prm.enter_subsection("Boundary conditions");
  prm.set("Initial displacement", "0.5*x");
  prm.leave_subsection();
  // At t = 1 the oscillation turns (v = 0), where the phase error hides;
  // t = 0.6 is mid-swing.
  const double        T         = 0.6;
  const double        reference = neo_hookean_reference(0.5, T);
  std::vector<double> nonlinear_errors;
  for (const double step : {0.01, 0.005, 0.0025})
    nonlinear_errors.push_back(
      std::abs(final_displacement(prm, step, T) - reference));
  const double linearly_implicit = final_displacement(prm, 0.01, T);
  // The W-method: one factorization for 8 steps.
  prm.enter_subsection("Time integration");
  prm.enter_subsection("Linearly implicit Euler");
  prm.set("Factorization interval", "8");
  prm.leave_subsection();
  prm.leave_subsection();
  std::vector<double> kept_errors;
  for (const double step : {0.01, 0.005, 0.0025})
    kept_errors.push_back(
      std::abs(final_displacement(prm, step, T) - reference));
  const double kept = final_displacement(prm, 0.01, T);
  prm.enter_subsection("Time integration");
  prm.set("Integrator", "backward Euler");
  prm.leave_subsection();
  const double backward_euler = final_displacement(prm, 0.01, T);
  std::cout.rdbuf(screen);

  check_order(linear_errors, "linear bar against u = 0.01 cos(sqrt(3) t)");
  check_order(nonlinear_errors,
              "neo-Hookean bar (F from 1.5 to 0.58) against RK4 reference");
  check_order(kept_errors,
              "neo-Hookean bar, one factorization per 8 steps, against RK4 "
              "reference");
  tissuefem_tests::check(std::abs(kept - linearly_implicit) > 1e-8,
                         "neo-Hookean bar: kept factorizations change the "
                         "answer (they are used)",
                         "difference "
                           + std::to_string(kept - linearly_implicit));
  tissuefem_tests::check(
    std::abs(linearly_implicit - backward_euler) > 1e-8,
    "neo-Hookean bar: one linear solve per step differs from converged "
    "backward Euler",
    "difference " + std::to_string(linearly_implicit - backward_euler));
  return tissuefem_tests::exit_status();
}
