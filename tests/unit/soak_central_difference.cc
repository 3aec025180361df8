// Soak test: 100,000 steps of the undamped central difference scheme
// (Jeffrey eqs 10-11 with c = 0, lumped mass) on a clamped linear elastic
// plate. For the linear system M (u+ - 2u + u-)/h^2 = -K u with constant h
// and symmetric K the shadow energy
//
//   H_n = 1/2 v^T M v + 1/2 u_{n+1}^T K u_n,  v = (u_{n+1} - u_n)/h,
//
// is conserved exactly: H_n - H_{n-1} = 1/2 (u_{n+1} - u_{n-1})^T (M (u_{n+1}
// - 2u_n + u_{n-1})/h^2 + K u_n) = 0. Over N steps only round-off changes
// it, as a random walk of about sqrt(N) eps kappa relative, kappa the
// condition of a step (here well below 1e3): below 1e-10 relative for N =
// 1e5. A drift of the scheme (wrong lumped mass, a step-size change, an
// energy leak in the force) shows at once. The ordinary energy E_n =
// 1/2 v^T M v + 1/2 u^T K u, which the scheme does not conserve, must stay
// within the bound of its oscillation about H: |E_n - H_n| = 1/2 |u_{n+1}^T
// K (u_{n+1} - u_n)| <= h omega_max H (omega_max h < 2 by stability);
// the test prints the largest relative deviation of H (must be below
// 1e-10) and checks that E never leaves [H (1 - h omega_max), H (1 + h
// omega_max)] with omega_max from the Rayleigh quotient bound of the
// element matrices.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/app/parameters.h>

#include <iostream>
#include <sstream>

#include "../tests.h"
#include "solid_scene.h"

using namespace dealii;
using namespace tissuefem;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ParameterHandler                 prm;
  declare_all_parameters(prm);
  prm.parse_input_from_string(R"(
    set Dimension = 2
    subsection Geometry
      set Lower corner = 0, 0
      set Upper corner = 2, 1
      set Subdivisions = 4, 2
    end
    subsection Materials
      set Model           = linear elastic
      set Young's modulus = 1
      set Poisson's ratio = 0.3
      set Density         = 1
    end
    subsection Boundary conditions
      set Dirichlet            = 0: xy: 0; 0
      set Initial displacement = 0.01*x*x; 0.005*x*y
    end
    subsection Time integration
      set Integrator = damped central difference
      set Time step  = 0.05
    end
  )");
  tissuefem_tests::SolidScene<2> scene(prm);
  auto                          &solid      = *scene.solid;
  time::Context                  context    = scene.context();
  auto                           integrator = scene.integrator(prm);
  time::State                    state;
  solid.initial_state(state.u, state.v);
  {
    // The integrator's report of its critical step stays out of the
    // compared output.
    std::ostringstream muted;
    auto              *screen = std::cout.rdbuf(muted.rdbuf());
    integrator->initialize(context, state);
    std::cout.rdbuf(screen);
  }
  const VectorType &mass = solid.lumped_mass();
  const double      h    = 0.05;

  // K u from the internal force (linear model), on the free entries only.
  auto stiffness_times = [&](const VectorType &u) {
    VectorType f;
    solid.internal_force(u, f);
    solid.zero_constrained_entries(f);
    return f;
  };
  auto kinetic = [&](const VectorType &v) {
    double sum = 0;
    for (const auto i : v.locally_owned_elements())
      sum += mass[i] * v[i] * v[i];
    return 0.5 * sum;
  };
  // omega_max^2 <= max over dofs of (row sum of |K|) / m (Gershgorin).
  double omega_max = 0;
  {
    VectorType e(state.u), row(state.u);
    e = 0;
    for (const auto i : e.locally_owned_elements())
      {
        e[i] = 1;
        row  = stiffness_times(e);
        e[i] = 0;
        if (row[i] == 0)
          continue;
        tissuefem_tests::raise(omega_max, std::sqrt(row.l1_norm() / mass[i]));
      }
  }

  const unsigned int n_steps = 100000;
  double             H0 = 0, worst_H = 0, worst_E = 0;
  VectorType         before;
  for (unsigned int n = 1; n <= n_steps; ++n)
    {
      const bool measure = n == 1 || n % 100 == 0;
      if (measure)
        before = state.u;
      integrator->advance(state, 1e300);
      if (!measure)
        continue;
      const double T = kinetic(state.v);
      const double H = T + 0.5 * (stiffness_times(before) * state.u);
      const double E = T + 0.5 * (stiffness_times(state.u) * state.u);
      if (n == 1)
        H0 = H;
      tissuefem_tests::raise(worst_H, std::abs(H - H0) / H0);
      tissuefem_tests::raise(worst_E, std::abs(E - H) / H0);
    }
  tissuefem_tests::check_small(
    worst_H, 1e-10, "shadow energy over 1e5 steps (relative change)");
  tissuefem_tests::check(worst_E <= h * omega_max,
                         "energy stays within h omega_max of the shadow "
                         "energy",
                         "deviation " + std::to_string(worst_E) + ", bound "
                           + std::to_string(h * omega_max));
  return tissuefem_tests::exit_status();
}
