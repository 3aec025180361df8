// The three-field update of the mean dilatation (F-bar) element
// (solid/three_field_dilatation.h, 'Materials/Mean dilatation/Update'),
// on Cook's membrane at nu = 0.4999 (parameters/cook_membrane.prm).
//
// 1. At a consistent state (the cell unknowns just set from u) the
//    three-field residual and Jacobian are the condensed element's, to
//    1e-12 relative: there the two Newton steps coincide.
// 2. Newton's method on the three-field equations converges
//    quadratically: the whole load in one solve from rest, full Newton
//    with full steps, each residual norm after the first step at most
//    10 e_max (e_k-1 / e_max)^2 while above round-off. A prediction that got a
//    row wrong (the constraint residual r left out of dtheta, say) converges
//    linearly or not at all. The answer is the condensed element's (20 load
//    steps) to 1e-8 relative in the largest nodal displacement: the same
//    discrete equations.
// 3. The issue's adaptive run (stress-jump indicator from 4 x 4 cells to
//    about 1500, steps of 0.05): no step is halved (the condensed update
//    halves steps after mesh changes and during the release of the
//    carried dilatation), and the tip deflection is within 1 % of 6.9347,
//    the converged value of FEniCS's Taylor-Hood P2-P1
//    (doc/peers/cook_membrane_fenics.py).

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/app/parameters.h>
#include <tissuefem/problems/interface.h>

#include "../tests.h"
#include "cook_membrane.h"
#include "solid_scene.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

using namespace dealii;
using namespace tissuefem;

namespace
{
  /// Cook's membrane on 16 x 16 cells.
  std::string
  cook(const std::string &extra)
  {
    return tissuefem_tests::cook_membrane("16, 16", extra);
  }


  /// The relative Frobenius distance of two matrices with one pattern.
  double
  matrix_distance(const MatrixType &a, const MatrixType &b)
  {
    double difference = 0, size = 0;
    for (auto ia = a.begin(), ib = b.begin(); ia != a.end(); ++ia, ++ib)
      {
        difference += std::pow(ia->value() - ib->value(), 2);
        size += std::pow(ib->value(), 2);
      }
    return std::sqrt(Utilities::MPI::sum(difference, MPI_COMM_WORLD)
                     / Utilities::MPI::sum(size, MPI_COMM_WORLD));
  }


  /// Solves the quasistatic run to t = 1 in steps of @p step with the
  /// given update; the displacement at the end.
  VectorType
  solve_cook(const std::string &update, const double step)
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string(cook(
      "subsection Time integration\n set Time step = " + std::to_string(step)
      + "\nend\nsubsection Materials\n subsection Mean dilatation\n set "
      + "Update = " + update + "\n end\nend\n"));
    tissuefem_tests::SolidScene<2> scene(prm);
    auto                          &solid      = *scene.solid;
    auto                           integrator = scene.integrator(prm);
    auto                           context    = scene.context();
    time::State                    state;
    solid.initial_state(state.u, state.v);
    integrator->initialize(context, state);
    while (state.time < 1 - 1e-12)
      integrator->advance(state, 1.);
    return state.u;
  }


  void
  check_consistent_state(const VectorType &u_end)
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string(cook(""));
    tissuefem_tests::SolidScene<2> scene(prm);
    auto                          &solid = *scene.solid;
    // The answer at t = 1 under half the load: far from equilibrium.
    const double t = 0.5;
    VectorType   r_condensed, r_three_field;
    solid.implicit_residual(u_end, u_end, 0., t, r_condensed, true);
    MatrixType j_condensed;
    j_condensed.copy_from(solid.jacobian());
    solid::IterationUnknowns *unknowns = solid.iteration_unknowns();
    unknowns->begin_iterations(t);
    solid.implicit_residual(u_end, u_end, 0., t, r_three_field, true);
    unknowns->end_iterations(false);
    VectorType difference(r_three_field);
    difference -= r_condensed;
    tissuefem_tests::check_small(difference.l2_norm() / r_condensed.l2_norm(),
                                 1e-12,
                                 "consistent state: residual as condensed");
    tissuefem_tests::check_small(matrix_distance(solid.jacobian(), j_condensed),
                                 1e-12,
                                 "consistent state: Jacobian as condensed");
  }


  /// Newton from rest to the whole load, full Newton, three-field.
  void
  check_quadratic_convergence(const VectorType &u_condensed)
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string(cook(R"(
    subsection Newton solver
      set Jacobian reuse              = false
      set Absolute residual tolerance = 1e-9
      set Line search steps           = 0
    end
    )"));
    tissuefem_tests::SolidScene<2> scene(prm);
    auto                          &solid = *scene.solid;
    VectorType                     u, v;
    solid.initial_state(u, v);
    const VectorType rest(u);
    const double     t        = 1;
    auto            *unknowns = solid.iteration_unknowns();
    unknowns->begin_iterations(0.);
    solvers::NewtonHooks hooks;
    hooks.predict = [&](const VectorType &du) { unknowns->predict_update(du); };
    hooks.trial = [&](const double alpha) { unknowns->set_step_length(alpha); };
    const auto result = solvers::solve_newton(
      scene.newton_parameters,
      u,
      [&](const VectorType &x, VectorType &r, const bool jacobian) {
        solid.implicit_residual(x, rest, 0., t, r, jacobian);
      },
      [&](VectorType &x, const VectorType &b, const bool refactorize) {
        scene.linear_solver->solve(solid.jacobian(), x, b, refactorize);
      },
      {},
      solid.length_scale(),
      false,
      &hooks);
    unknowns->end_iterations(result.converged);
    tissuefem_tests::check(result.converged,
                           "whole load in one Newton solve: converges",
                           result.failure);
    // The first full step from rest overshoots (the residual rises, as
    // the integrator's boundary lifting also takes it); from then on
    // each norm is at most 10 e_max (e_k-1 / e_max)^2 while above
    // round-off.
    const auto  &e       = result.residual_norms;
    const double e_max   = *std::max_element(e.begin(), e.end());
    bool         ok      = result.converged && e.size() >= 4;
    std::string  history = "residual norms";
    for (unsigned int k = 0; k < e.size(); ++k)
      {
        std::ostringstream norm;
        norm << ' ' << e[k];
        history += norm.str();
        if (k > 1 && e[k - 1] > 1e-7 * e_max)
          ok = ok && e[k] <= 10 * e_max * std::pow(e[k - 1] / e_max, 2);
      }
    tissuefem_tests::check(ok, "Newton converges quadratically", history);
    VectorType difference(u);
    difference -= u_condensed;
    tissuefem_tests::check_small(difference.linfty_norm()
                                   / u_condensed.linfty_norm(),
                                 1e-8,
                                 "the condensed element's answer");
  }


  /// The issue's adaptive run, through the elasticity problem.
  void
  check_adaptive_run()
  {
    const auto run
      = tissuefem_tests::run_adaptive_cook(1500,
                                           "adaptive_cook_three_field",
                                           "subsection Newton solver\n"
                                           " set Maximum iterations = 25\n"
                                           "end\n");
    tissuefem_tests::check(run.failure.empty() && run.time == 1,
                           "adaptive run reaches t = 1",
                           run.failure);
    // Screen lines name halved steps ("retrying with dt = ...").
    const auto halved = run.screen.find("Newton failed");
    tissuefem_tests::check(halved == std::string::npos,
                           "adaptive run: no step halved",
                           halved == std::string::npos
                             ? ""
                             : run.screen.substr(halved, 200));
    const double error = std::abs(run.tip - 6.9347) / 6.9347;
    tissuefem_tests::check(error < 0.01,
                           "adaptive run: tip deflection within 1 % of 6.9347",
                           std::to_string(run.tip));
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const VectorType                 u_condensed = solve_cook("condensed", 0.05);
  check_consistent_state(u_condensed);
  check_quadratic_convergence(u_condensed);
  check_adaptive_run();
  return tissuefem_tests::exit_status();
}
