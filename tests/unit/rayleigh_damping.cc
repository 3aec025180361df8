// Rayleigh damping ('Time integration/Rayleigh mass damping' alpha and
// 'Rayleigh stiffness damping' beta, damping force (alpha M + beta K) v)
// on the one-element bar of the order tests: a 1D bar (0, 1) clamped at
// x = 0, rho = 1, consistent mass, so that the free node has mass m = 1/3
// and internal force f(u) = u (linear elastic, E = 1, nu = 0) or
// f(u) = mu (F - 1/F), F = 1 + u, mu = 1/2 (neo-Hookean, lambda = 0).
// alpha = 2, beta = 0.05: with h = 0.01 the stiffness term scales the step's
// equations by kappa = 1 + beta/h = 6, which the integrators fold in
// (ImplicitOneStep::damp()).
//
// Expected values, all written out here independently of the library:
// 1. The damped oscillator m u'' + (alpha m + beta k) u' + k u = 0 in
//    closed form (linear bar, u(0) = 0.01 at rest): backward Euler and
//    linearly implicit Euler at t = 1 converge to it with observed order 1
//    (h = 0.02, 0.01, 0.005; within 0.2).
// 2. Step by step over 50 steps of h = 0.01, relative 1e-9:
//    - backward Euler, the textbook damped step m (u1 - u0 - h v0)/h^2 +
//      alpha m (u1 - u0)/h + beta (f(u1) - f(u0))/h + f(u1) = 0, solved
//      here by scalar Newton to round-off;
//    - linearly implicit Euler in SOFA's velocity form (EulerImplicitSolver):
//      [(1 + h alpha) m + h (h + beta) K] dv = -h f(u0) - h (h K + alpha m +
//      beta K) v0, K = f'(u0), v1 = v0 + dv, u1 = u0 + h v1;
//    both on the linear bar and the neo-Hookean bar started at F = 1.5.
// 3. The damping work each step reports against backward Euler's energy
//    identity on the linear bar: the damping force takes out exactly
//    (alpha m + beta k) (u1 - u0)^2 / h per step (relative 1e-9), and the
//    energy lost per step is that plus m/2 (v1 - v0)^2 + k/2 (u1 - u0)^2.
// 4. The reaction at the clamp (Solid::reaction_forces with the state's
//    damping), step by step against the clamped node's row of the damped
//    equation: m01 (a1 + alpha v1) - f(u1) - beta/h (f(u1) - f(u0)), the
//    consistent mass coupling m01 = 1/6, a1 = (v1 - v0)/h, v1 = (u1 -
//    u0)/h (relative 1e-9 of the largest elastic force |f(u1)| met): the
//    force a clamp or a grasping tool must supply includes the damping
//    force. Backward Euler on both bars; the linearly implicit Euler on the
//    linear bar (its damping term linearizes f at u0, the same there).

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/app/parameters.h>

#include "../tests.h"
#include "solid_scene.h"

#include <cmath>
#include <functional>
#include <iostream>
#include <sstream>

using namespace dealii;
using namespace tissuefem;

namespace
{
  const double m = 1. / 3, alpha = 2, beta = 0.05, mu = 0.5;

  struct Bar
  {
    std::function<double(double)> force, stiffness;
  };

  const Bar linear{[](const double u) { return u; },
                   [](const double) { return 1.; }};
  const Bar neo_hookean{[](const double u) {
                          const double F = 1 + u;
                          return mu * (F - 1. / F);
                        },
                        [](const double u) {
                          const double F = 1 + u;
                          return mu * (1. + 1. / (F * F));
                        }};

  /// One damped backward Euler step of the scalar bar, by Newton.
  std::pair<double, double>
  backward_euler_step(const Bar   &bar,
                      const double u0,
                      const double v0,
                      const double h)
  {
    const auto residual = [&](const double u) {
      return m * (u - u0 - h * v0) / (h * h) + alpha * m * (u - u0) / h
             + beta * (bar.force(u) - bar.force(u0)) / h + bar.force(u);
    };
    double u = u0 + h * v0;
    for (unsigned int i = 0; i < 50; ++i)
      {
        const double slope
          = m / (h * h) + alpha * m / h + (1 + beta / h) * bar.stiffness(u);
        const double du = -residual(u) / slope;
        u += du;
        if (std::abs(du) < 1e-16 * (1 + std::abs(u)))
          break;
      }
    return {u, (u - u0) / h};
  }

  /// One step of SOFA's EulerImplicitSolver with Rayleigh damping.
  std::pair<double, double>
  sofa_step(const Bar &bar, const double u0, const double v0, const double h)
  {
    const double K = bar.stiffness(u0);
    const double dv
      = (-h * bar.force(u0) - h * (h * K + alpha * m + beta * K) * v0)
        / ((1 + h * alpha) * m + h * (h + beta) * K);
    const double v1 = v0 + dv;
    return {u0 + h * v1, v1};
  }

  /// The free node's entry (the clamped node's is 0).
  double
  free_entry(const VectorType &x)
  {
    Vector<double> copy(x);
    return copy[0] + copy[1];
  }

  void
  set_integrator(ParameterHandler  &prm,
                 const std::string &integrator,
                 const double       step,
                 const double       end_time)
  {
    prm.enter_subsection("Time integration");
    prm.set("Integrator", integrator);
    prm.set("Time step", step);
    prm.set("End time", end_time);
    prm.set("Rayleigh mass damping", alpha);
    prm.set("Rayleigh stiffness damping", beta);
    prm.leave_subsection();
  }

  /// Runs @p integrator with steps @p h to @p end_time on the bar of
  /// @p prm; calls @p each_step(u0, v0, u1, v1, damping work, reaction at
  /// x = 0) per step.
  void
  run(ParameterHandler  &prm,
      const std::string &integrator,
      const double       h,
      const double       end_time,
      const std::function<void(double, double, double, double, double, double)>
        &each_step)
  {
    set_integrator(prm, integrator, h, end_time);
    tissuefem_tests::SolidScene<1> scene(prm);
    auto                           run   = scene.start(prm);
    auto                          &state = run->state;
    while (state.time < end_time * (1 - 1e-12))
      {
        const double u0 = free_entry(state.u), v0 = free_entry(state.v);
        const auto   report   = run->integrator->advance(state, end_time);
        const double reaction = scene.solid->reaction_forces(
          state.u, state.a, state.time, state.damping, {0})[0];
        each_step(u0,
                  v0,
                  free_entry(state.u),
                  free_entry(state.v),
                  report.damping_work,
                  reaction);
      }
  }

  /// The closed-form damped oscillation of the linear bar from 0.01 at
  /// rest, at @p t.
  double
  damped_oscillator(const double t)
  {
    const double omega   = std::sqrt(1. / m);
    const double zeta    = alpha / (2 * omega) + beta * omega / 2;
    const double omega_d = omega * std::sqrt(1 - zeta * zeta);
    const double u0      = 0.01;
    return std::exp(-zeta * omega * t)
           * (u0 * std::cos(omega_d * t)
              + zeta * omega * u0 / omega_d * std::sin(omega_d * t));
  }

  void
  check_order(ParameterHandler &prm, const std::string &integrator)
  {
    std::vector<double> errors;
    for (const double h : {0.02, 0.01, 0.005})
      {
        double last = 0;
        run(prm,
            integrator,
            h,
            1.,
            [&](double, double, double u1, double, double, double) {
              last = u1;
            });
        errors.push_back(std::abs(last - damped_oscillator(1.)));
      }
    const double order_1 = std::log2(errors[0] / errors[1]);
    const double order_2 = std::log2(errors[1] / errors[2]);
    tissuefem_tests::check(std::abs(order_1 - 1.) < 0.2
                             && std::abs(order_2 - 1.) < 0.2,
                           integrator
                             + ", linear bar against the damped oscillator "
                               "in closed form: observed order 1 within 0.2",
                           "orders " + std::to_string(order_1) + ", "
                             + std::to_string(order_2));
  }

  /// Step by step against the scalar recurrence @p step; on the linear
  /// bar also the damping work against the energy identity.
  void
  check_steps(
    ParameterHandler  &prm,
    const std::string &integrator,
    const Bar         &bar,
    const std::string &bar_name,
    const std::function<
      std::pair<double, double>(const Bar &, double, double, double)> &step)
  {
    double worst = 0, worst_work = 0, worst_balance = 0, worst_reaction = 0,
           largest_force = 0;
    const double h       = 0.01;
    run(prm,
        integrator,
        h,
        0.5,
        [&](double u0,
            double v0,
            double u1,
            double v1,
            double work,
            double reaction) {
          const auto [u_expected, v_expected] = step(bar, u0, v0, h);
          tissuefem_tests::raise(worst,
                                 std::abs(u1 - u_expected) / 0.01
                                   + std::abs(v1 - v_expected) / 0.1);
          const double velocity = (u1 - u0) / h, a1 = (velocity - v0) / h;
          const double expected = (a1 + alpha * velocity) / 6 - bar.force(u1)
                                  - beta / h * (bar.force(u1) - bar.force(u0));
          tissuefem_tests::raise(worst_reaction, std::abs(reaction - expected));
          largest_force = std::max(largest_force, std::abs(bar.force(u1)));
          if (&bar != &linear)
            return;
          const double du         = u1 - u0;
          const double dissipated = (alpha * m + beta) * du * du / 0.01;
          tissuefem_tests::raise(worst_work,
                                 std::abs(work - dissipated) / dissipated);
          const double lost
            = m / 2 * (v0 * v0 - v1 * v1) + (u0 * u0 - u1 * u1) / 2;
          const double numerical = m / 2 * (v1 - v0) * (v1 - v0) + du * du / 2;
          tissuefem_tests::raise(worst_balance,
                                 std::abs(lost - work - numerical)
                                   / dissipated);
        });
    tissuefem_tests::check_small(worst,
                                 1e-9,
                                 integrator + ", " + bar_name
                                   + ": 50 steps against the recurrence "
                                     "written out, relative error");
    if (integrator == "backward Euler" || &bar == &linear)
      tissuefem_tests::check_small(
        worst_reaction / largest_force,
        1e-9,
        integrator + ", " + bar_name
          + ": reaction at the clamp, damping force included, against its "
            "row of the damped equation, relative");
    if (&bar == &linear)
      {
        tissuefem_tests::check_small(
          worst_work,
          1e-9,
          integrator
            + ", linear bar: damping work per step against "
              "(alpha m + beta k) (u1 - u0)^2 / h, relative");
        tissuefem_tests::check_small(
          worst_balance,
          1e-8,
          integrator
            + ", linear bar: energy lost per step = damping work "
              "+ m/2 dv^2 + k/2 du^2, relative to the work");
      }
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ParameterHandler                 prm;
  declare_all_parameters(prm);
  prm.parse_input_from_string(tissuefem_tests::one_element_bar(""));
  prm.enter_subsection("Newton solver");
  prm.set("Relative residual tolerance", "1e-13");
  prm.set("Absolute residual tolerance", "1e-13");
  prm.leave_subsection();

  check_order(prm, "backward Euler");
  check_order(prm, "linearly implicit Euler");
  check_steps(prm, "backward Euler", linear, "linear bar", backward_euler_step);
  check_steps(prm, "linearly implicit Euler", linear, "linear bar", sofa_step);

  prm.enter_subsection("Materials");
  prm.set("Model", "neo-Hookean");
  prm.leave_subsection();
  prm.enter_subsection("Boundary conditions");
  prm.set("Initial displacement", "0.5*x");
  prm.leave_subsection();
  check_steps(
    prm, "backward Euler", neo_hookean, "neo-Hookean bar", backward_euler_step);
  check_steps(
    prm, "linearly implicit Euler", neo_hookean, "neo-Hookean bar", sofa_step);
  return tissuefem_tests::exit_status();
}
