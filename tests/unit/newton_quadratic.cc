// Newton's method converges quadratically on the problem session's 2D example
// (robust neo-Hookean square, u = (sin t, sin t) on X1 = +-1, backward
// Euler). One large step (dt = 0.1) from rest, starting from the rigid
// translation,, so that several iterations lie above round-off. With an exact
// Jacobian the observed order p_k = log(r_{k+1}/r_k) / log(r_k/r_{k-1}) of the
// residual norms r_k must approach 2; a wrong tangent shows p = 1. The same
// step is repeated with the hand-coded tangent: the converged displacements
// must agree to the Newton tolerance. Then with 'Jacobian reuse' (modified
// Newton): it must reach the same step with fewer Jacobians than
// iterations.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/app/parameters.h>
#include <tissuefem/solvers/newton.h>

#include "../tests.h"
#include "solid_scene.h"

using namespace dealii;
using namespace tissuefem;

namespace
{
  const char *scene = R"(
    set Dimension = 2
    subsection Geometry
      set Lower corner = -1, -1
      set Upper corner = 1, 1
      set Subdivisions = 8, 8
    end
    subsection Boundary conditions
      set Dirichlet = 0: xy: sin(t); sin(t) | 1: xy: sin(t); sin(t)
    end
    subsection Newton solver
      set Absolute residual tolerance = 0
      set Relative residual tolerance = 1e-12
      set Update tolerance = 0
      set Displacement tolerance = 0
      set Jacobian reuse = false
      set Maximum iterations = 12
    end
    subsection Materials
      set Tangent = automatic differentiation
    end
  )";

  solvers::NewtonResult
  one_step(ParameterHandler &prm, Vector<double> &u_result)
  {
    tissuefem_tests::SolidScene<2> scene(prm);
    auto                          &solid         = *scene.solid;
    auto                          &linear_solver = *scene.linear_solver;

    const double dt = 0.1;
    VectorType   u, u_tilde;
    solid.initialize_vector(u);
    solid.initialize_vector(u_tilde);
    // Initial guess: the rigid translation by the boundary displacement,
    // a guess from which Newton's convergence is local.
    u = std::sin(dt);
    solid.apply_dirichlet_values(dt, u);
    const auto result = solvers::solve_newton(
      scene.newton_parameters,
      u,
      [&](const VectorType &x, VectorType &r, bool jacobian) {
        solid.implicit_residual(x, u_tilde, 1. / (dt * dt), dt, r, jacobian);
      },
      [&](VectorType &x, const VectorType &b, const bool refactorize) {
        linear_solver.solve(solid.jacobian(), x, b, refactorize);
      },
      {},
      solid.length_scale());
    u_result.reinit(u.size());
    for (unsigned int i = 0; i < u.size(); ++i)
      u_result[i] = u[i];
    return result;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ParameterHandler                 prm;
  declare_all_parameters(prm);
  prm.parse_input_from_string(scene);
  Vector<double> u_ad, u_hand;

  // The observed order at the last iteration whose residual is well above
  // round-off (an exact Jacobian gives about 2 there; a wrong one about 1).
  auto final_order = [](const std::vector<double> &r) {
    double order = 0;
    for (unsigned int k = 1; k + 1 < r.size(); ++k)
      if (r[k + 1] > 1e-12 * r[0])
        order = std::log(r[k + 1] / r[k]) / std::log(r[k] / r[k - 1]);
    return order;
  };

  const auto ad = one_step(prm, u_ad);
  tissuefem_tests::check(ad.converged, "AD tangent: Newton converged");
  tissuefem_tests::check(
    final_order(ad.residual_norms) > 1.8,
    "AD tangent: observed order of convergence exceeds 1.8",
    "order " + std::to_string(final_order(ad.residual_norms)));

  prm.enter_subsection("Materials");
  prm.set("Tangent", "hand coded");
  prm.leave_subsection();
  const auto hand = one_step(prm, u_hand);
  tissuefem_tests::check(hand.converged,
                         "hand-coded tangent: Newton converged");
  tissuefem_tests::check(
    final_order(hand.residual_norms) > 1.8,
    "hand-coded tangent: observed order of convergence exceeds 1.8",
    "order " + std::to_string(final_order(hand.residual_norms)));
  u_hand -= u_ad;
  tissuefem_tests::check_small(
    u_hand.linfty_norm() / u_ad.linfty_norm(),
    1e-10,
    "hand-coded and AD tangents give the same step (relative)");

  // Modified Newton ('Jacobian reuse'): the same step to the tolerance,
  // with fewer Jacobians (factorizations) than iterations, each iteration
  // with a kept Jacobian contracting the residual at least 4-fold.
  prm.enter_subsection("Newton solver");
  prm.set("Jacobian reuse", true);
  prm.leave_subsection();
  Vector<double> u_reuse;
  const auto     reuse = one_step(prm, u_reuse);
  tissuefem_tests::check(reuse.converged, "Jacobian reuse: Newton converged");
  tissuefem_tests::check(reuse.jacobians < reuse.iterations,
                         "Jacobian reuse: fewer Jacobians than iterations",
                         std::to_string(reuse.jacobians) + " Jacobians, "
                           + std::to_string(reuse.iterations) + " iterations");
  u_reuse -= u_ad;
  tissuefem_tests::check_small(
    u_reuse.linfty_norm() / u_ad.linfty_norm(),
    1e-10,
    "Jacobian reuse gives the same step as full Newton (relative)");
  return tissuefem_tests::exit_status();
}
