// Energy of a body bouncing on a rigid floor (contact/penalty_contact.h).
// A linear elastic block (1 x 0.5, 4 x 2 Q1 cells, E = 1000, nu = 0.3,
// rho = 1) starts 0.05 above a frictionless penalty floor, moving down at 1
// and sideways at 0.5, under gravity (0, -9.81), and falls, hits the floor,
// bounces and slides, over 0.5 time units. Its potential V(u) = int Psi dV
// + E_contact(u) - f_ext . u is convex (quadratic elasticity, k/2 g^2 on a
// plane, a dead load). Checked, beside the floor being hit (a force at
// some step) and left again (none at a later step):
// - backward Euler (100 steps of 0.005) dissipates: V + 1/2 v.M v can only
//   fall from step to step, by V(u_n) - V(u_n+1) - grad V(u_n+1) . (u_n -
//   u_n+1) + 1/2 |v_n+1 - v_n|_M^2 >= 0. The total never rises (relative
//   to its start, allowing Newton's residual of 1e-10), and some of it is
//   dissipated.
// - the undamped central difference (explicit, lumped mass, penalty factor
//   1; its kinetic energy that of the lumped mass) conserves it up to its
//   own error: the largest change from the start stays below 3 % and falls
//   with dt (measured 2.35e-2, 1.16e-2 and 5.8e-3 at dt = 4e-4, 2e-4 and
//   1e-4: first order, as the scheme's velocity (u_n+1 - u_n) / h is).
//   With the contact force 1.5 times the energy's gradient, the change is
//   0.49 at every step size.
// Both mean that the contact force is the gradient of the energy the run
// keeps.

#include <deal.II/base/mpi.h>

#include <tissuefem/app/parameters.h>

#include "../tests.h"
#include "solid_scene.h"

#include <cmath>
#include <sstream>

using namespace tissuefem_tests;

namespace
{
  struct Outcome
  {
    /// The largest rise from one step to the next and the largest
    /// departure from the start (either way), relative to the starting
    /// energy; the final energy over the start.
    double       worst_rise = 0, worst_change = 0, end = 0;
    unsigned int touched = 0, left = 0;
  };

  Outcome
  run(const std::string &integrator_name, const double dt)
  {
    ParameterHandler prm;
    tissuefem::declare_all_parameters(prm);
    std::ostringstream text;
    text << R"(
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
      set Penalty factor = )"
         << (integrator_name == "backward Euler" ? 100 : 1) << R"(
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
      set Integrator = )"
         << integrator_name << R"(
      set End time   = 0.5
      set Time step  = )"
         << dt << R"(
    end
  )";
    prm.parse_input_from_string(text.str());
    std::ostringstream muted;
    auto              *screen = std::cout.rdbuf(muted.rdbuf());
    Outcome            outcome;
    {
      SolidScene<2> scene(prm);
      auto         &solid  = *scene.solid;
      const auto    run    = scene.start(prm);
      time::State  &state  = run->state;
      const bool    lumped = integrator_name != "backward Euler";
      const auto    total  = [&]() {
        VectorType none(state.u);
        none = 0;
        if (!lumped)
          return solid.implicit_energy(state.u, none, 0., state.time)
                 + solid.kinetic_energy(state.v);
        // The explicit scheme's own kinetic energy is the lumped mass's.
        const VectorType &m       = solid.lumped_mass();
        double            kinetic = 0;
        for (const auto i : state.v.locally_owned_elements())
          kinetic += 0.5 * m[i] * state.v[i] * state.v[i];
        return solid.implicit_energy(state.u, none, 0., state.time)
               + Utilities::MPI::sum(kinetic, MPI_COMM_WORLD);
      };
      const double start    = total();
      double       previous = start;
      while (state.time < 0.5 - 1e-12)
        {
          run->integrator->advance(state, 0.5);
          const double now = total();
          raise(outcome.worst_rise, (now - previous) / std::abs(start));
          raise(outcome.worst_change, std::abs(now - start) / std::abs(start));
          previous = now;
          VectorType ghosted;
          scene.discretization->initialize_vector(ghosted, true);
          ghosted = state.u;
          const double force
            = scene.obstacle_contact->report(ghosted, state.time)[0].force[1];
          if (force > 0)
            ++outcome.touched;
          else if (outcome.touched > 0)
            ++outcome.left;
        }
      outcome.end = previous / start;
    }
    std::cout.rdbuf(screen);
    return outcome;
  }

  void
  check_bounce(const Outcome &o, const std::string &name)
  {
    check(o.touched > 0, name + ": the block hits the floor", "never touched");
    check(o.left > 0, name + ": and leaves it again", "never left");
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const tissuefem_tests::OneWriter one_writer;
  const Outcome                    implicit = run("backward Euler", 0.005);
  check_bounce(implicit, "backward Euler");
  check_small(std::max(implicit.worst_rise, 0.),
              1e-9,
              "backward Euler: kinetic + potential energy never rises "
              "(largest rise over the starting energy)");
  check(implicit.end < 0.9,
        "backward Euler: and some of it is dissipated",
        "end over start " + std::to_string(implicit.end));

  const Outcome coarse = run("damped central difference", 4e-4);
  const Outcome fine   = run("damped central difference", 2e-4);
  check_bounce(coarse, "central difference");
  check_small(coarse.worst_change,
              3e-2,
              "central difference: largest change of the energy from the "
              "start (relative)");
  check(coarse.worst_change > 1.8 * fine.worst_change,
        "central difference: the change falls by more than 1.8 when dt "
        "halves",
        std::to_string(coarse.worst_change) + " then "
          + std::to_string(fine.worst_change));
  return exit_status();
}
