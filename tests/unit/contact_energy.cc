// Energy of a body bouncing on a rigid floor (contact/penalty_contact.h)
// under backward Euler. A linear elastic block (1 x 0.5, 4 x 2 Q1 cells,
// E = 1000, nu = 0.3, rho = 1) starts 0.05 above a frictionless penalty
// floor, moving down at 1 and sideways at 0.5, under gravity (0, -9.81),
// and falls, hits the floor, bounces and slides, for 100 steps of 0.005.
// Its potential V(u) = int Psi dV + E_contact(u) - f_ext . u is convex
// (quadratic elasticity, k/2 g^2 on a plane, a dead load), so backward
// Euler dissipates: V + 1/2 v.M v can only fall from step to step, by
// V(u_n) - V(u_n+1) - grad V(u_n+1) . (u_n - u_n+1) + 1/2 |v_n+1 - v_n|_M^2
// >= 0. Checked: the total never rises (relative to its start, allowing
// Newton's residual of 1e-10), the floor is hit (a force at some step)
// and left again (no force at a later step): the contact force is the
// gradient of the energy the run keeps, and the bounce works.

#include <deal.II/base/mpi.h>

#include <tissuefem/base/application.h>

#include "../tests.h"
#include "solid_scene.h"

#include <cmath>
#include <sstream>

using namespace tissuefem_tests;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ParameterHandler                 prm;
  tissuefem::declare_all_parameters(prm);
  prm.parse_input_from_string(R"(
    set Dimension = 2
    subsection Geometry
      set Lower corner = 0, 0.05
      set Upper corner = 1, 0.55
      set Subdivisions = 4, 2
    end
    subsection Materials
      set Model           = linear elastic
      set Young's modulus = 1000
      set Poisson's ratio = 0.3
      set Density         = 1
    end
    subsection Boundary conditions
      set Gravity          = 0, -9.81
      set Initial velocity = 0.5; -1
    end
    subsection Contact
      subsection Obstacle 1
        set Shape = half-space
        set Name  = floor
        subsection half-space
          set Point  = 0, 0
          set Normal = 0, 1
        end
      end
    end
    subsection Time integration
      set Integrator = backward Euler
      set End time   = 0.5
      set Time step  = 0.005
    end
  )");
  std::ostringstream muted;
  auto              *screen = std::cout.rdbuf(muted.rdbuf());
  SolidScene<2>      scene(prm);
  auto              &solid      = *scene.solid;
  time::Context      context    = scene.context();
  auto               integrator = scene.integrator(prm);
  time::State        state;
  solid.initial_state(state.u, state.v);
  integrator->initialize(context, state);
  const auto total = [&]() {
    VectorType none(state.u);
    none = 0;
    return solid.implicit_energy(state.u, none, 0., state.time)
           + solid.kinetic_energy(state.v);
  };
  const double start    = total();
  double       previous = start, worst_rise = 0;
  unsigned int touched = 0, left = 0;
  while (state.time < 0.5 - 1e-12)
    {
      integrator->advance(state, 0.5);
      const double now = total();
      raise(worst_rise, (now - previous) / std::abs(start));
      previous = now;
      VectorType ghosted;
      scene.discretization->initialize_vector(ghosted, true);
      ghosted = state.u;
      const double force
        = scene.obstacle_contact->report(ghosted, state.time)[0].force[1];
      if (force > 0)
        ++touched;
      else if (touched > 0)
        ++left;
    }
  std::cout.rdbuf(screen);
  check(touched > 0, "the block hits the floor", "never touched");
  check(left > 0, "and leaves it again", "never left");
  check_small(std::max(worst_rise, 0.),
              1e-9,
              "backward Euler: kinetic + potential energy never rises "
              "(largest rise over the starting energy)");
  check(previous < 0.9 * start,
        "and some of it is dissipated",
        "end " + std::to_string(previous) + ", start " + std::to_string(start));
  return exit_status();
}
