// Coulomb friction against a rigid obstacle (contact/penalty_contact.h, by
// the augmented Lagrangian and by the penalty with its friction bound
// settled by re-solves, both with backward Euler, and by the penalty with
// the damped central difference, undamped, its gravity ramped in over 0.05
// and its tolerances 1e-2) on the closed form of a block on an incline: a
// stiff block (E = 1e6, rho = 1; in 2D 1 x 0.25 in 8 x 2 Q1 cells, in 3D
// 1 x 0.25 x 0.5 in 4 x 1 x 2 boxes of P1 tetrahedra) at rest on a
// frictional floor, with gravity tilted by theta (the incline), integrated
// by backward Euler for 20 steps of 0.01. A rigid block sticks where tan
// theta <= mu and otherwise slides with a = g (sin theta - mu cos theta);
// backward Euler's discrete answer to a constant acceleration from rest
// is x_N = a dt^2 N (N + 1) / 2 exactly. Checked, on theta = 20 and 35
// degrees with mu = 0.5 (stick, slide) and without friction:
// - the mean displacement along the incline against x_N (relative, 1e-4;
//   the block's elastic shear and the penalty's tangential spring are
//   below 1e-5 of it);
// - sticking: the mean displacement below 1e-4 of the frictionless one;
// - the floor's force: sliding, tangential over normal = -mu (1e-6);
//   sticking, the tangential force balances the weight's component
//   along the incline (1e-4); normal force m g cos theta (1e-4).

#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>

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
    double mean_x = 0, tangential = 0, normal = 0;
  };

  /// How contact and time are treated, and the tolerance of the checks.
  struct Method
  {
    std::string contact, integrator;
    double      dt;
    /// 'Penalty factor' and 'Load factor' (the explicit steps ramp gravity
    /// in over 0.05, so that the undamped block settles on the floor
    /// instead of bouncing).
    std::string penalty_factor, load_factor;
    double      tolerance;
  };

  template <int dim>
  Outcome
  run(const double theta_degrees, const double mu, const Method &method)
  {
    const double       theta = theta_degrees * M_PI / 180;
    std::ostringstream text;
    const std::string  zero = dim == 3 ? ", 0" : "";
    text << std::setprecision(17) << "set Dimension = " << dim << R"(
      subsection Geometry
        set Cell type    = )"
         << (dim == 3 ? "simplex" : "hypercube") << R"(
        set Lower corner = 0, 0)"
         << zero << R"(
        set Upper corner = 1, 0.25)"
         << (dim == 3 ? ", 0.5" : "") << R"(
        set Subdivisions = )"
         << (dim == 3 ? "4, 1, 2" : "8, 2") << R"(
      end
      subsection Materials
        set Model           = linear elastic
        set Young's modulus = 1e6
        set Poisson's ratio = 0.3
        set Density         = 1
      end
      subsection Boundary conditions
        set Load factor = )"
         << method.load_factor << R"(
        set Gravity = )"
         << 9.81 * std::sin(theta) << ", " << -9.81 * std::cos(theta) << zero
         << R"(
      end
      subsection Contact
        set Method        = )"
         << method.contact << R"(
        set Gap tolerance = 1e-9
        set Penalty factor = )"
         << method.penalty_factor << R"(
        subsection Obstacle 1
          set Shape                = half-space
          set Name                 = incline
          set Friction coefficient = )"
         << mu << R"(
          subsection half-space
            set Point  = 0, 0)"
         << zero << R"(
            set Normal = 0, 1)"
         << zero << R"(
          end
        end
      end
      subsection Time integration
        set Integrator = )"
         << method.integrator << R"(
        set End time   = 0.2
        set Time step  = )"
         << method.dt << R"(
      end
    )";
    ParameterHandler prm;
    tissuefem::declare_all_parameters(prm);
    prm.parse_input_from_string(text.str());
    std::ostringstream muted;
    auto              *screen = std::cout.rdbuf(muted.rdbuf());
    Outcome            outcome;
    {
      SolidScene<dim> scene(prm);
      const auto      run = scene.start(prm);
      run->advance_to(0.2);
      const time::State &state = run->state;
      // The mean of the nodes' x displacements.
      ComponentMask along(dim, false);
      along.set(0, true);
      const IndexSet x_dofs
        = DoFTools::extract_dofs(scene.discretization->dof_handler, along);
      double sum = 0, count = 0;
      for (const auto i : state.u.locally_owned_elements())
        if (x_dofs.is_element(i))
          {
            sum += state.u[i];
            count += 1;
          }
      const MPI_Comm comm = MPI_COMM_WORLD;
      outcome.mean_x
        = Utilities::MPI::sum(sum, comm) / Utilities::MPI::sum(count, comm);
      VectorType ghosted;
      scene.discretization->initialize_vector(ghosted, true);
      ghosted            = state.u;
      const auto reports = scene.obstacle_contact->report(ghosted, state.time);
      outcome.tangential = reports[0].force[0];
      outcome.normal     = reports[0].force[1];
    }
    std::cout.rdbuf(screen);
    return outcome;
  }

  template <int dim>
  void
  check_incline(const double theta_degrees, const double mu, const Method &m)
  {
    const double theta = theta_degrees * M_PI / 180, g = 9.81, dt = m.dt;
    const double mass = dim == 3 ? 0.125 : 0.25;
    // From rest under a constant acceleration a, after N steps: backward
    // Euler's x_N = a dt^2 N (N + 1) / 2. Under the load factor min(t /
    // tau, 1) the central difference, exact for piecewise quadratic
    // motion, gives a times the factor's double integral, tau^2 / 6 + tau
    // (T - tau) / 2 + (T - tau)^2 / 2 at T = 0.2.
    const double N        = std::round(0.2 / dt);
    const bool   implicit = m.integrator == "backward Euler";
    const double tau = 0.05, T = 0.2;
    const auto   discrete = [&](const double a) {
      return implicit ? a * dt * dt * N * (N + 1) / 2
                        : a
                          * (tau * tau / 6 + tau * (T - tau) / 2
                             + (T - tau) * (T - tau) / 2);
    };
    const double       tolerance    = m.tolerance;
    const Outcome      frictionless = run<dim>(theta_degrees, 0, m);
    const Outcome      with         = run<dim>(theta_degrees, mu, m);
    std::ostringstream label;
    label << dim << "D, " << m.contact << ", " << m.integrator
          << ", theta = " << theta_degrees << " degrees, mu = " << mu;
    const std::string name = label.str();
    check_small(frictionless.mean_x / discrete(g * std::sin(theta)) - 1,
                tolerance,
                name + ": frictionless, slides with g sin theta");
    check_small(with.normal / (mass * g * std::cos(theta)) - 1,
                tolerance,
                name + ": normal force m g cos theta");
    if (std::tan(theta) <= mu)
      {
        check_small(with.mean_x / frictionless.mean_x,
                    tolerance,
                    name + ": sticks (displacement over the frictionless one)");
        check_small(with.tangential / (mass * g * std::sin(theta)) + 1,
                    tolerance,
                    name + ": friction balances m g sin theta");
      }
    else
      {
        const double a = g * (std::sin(theta) - mu * std::cos(theta));
        check_small(with.mean_x / discrete(a) - 1,
                    tolerance,
                    name + ": slides with g (sin theta - mu cos theta)");
        check_small(with.tangential / with.normal + mu,
                    implicit ? 1e-6 : tolerance,
                    name + ": sliding friction is -mu times the normal force");
      }
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  // Every figure is global: one process writes.
  const OneWriter one_writer;
  const Method    augmented{
    "augmented Lagrangian", "backward Euler", 0.01, "100", "1", 1e-4};
  const Method penalty{"penalty", "backward Euler", 0.01, "100", "1", 1e-4};
  const Method explicit_steps{"penalty",
                              "damped central difference",
                              2e-5,
                              "10",
                              "min(t / 0.05, 1)",
                              1e-2};
  for (const Method &m : {augmented, penalty})
    {
      check_incline<2>(20, 0.5, m);
      check_incline<2>(35, 0.5, m);
      check_incline<3>(20, 0.5, m);
      check_incline<3>(35, 0.5, m);
    }
  // Explicit steps: sticking only. A sliding undamped elastic block
  // vibrates in the friction-induced instability of elastic sliding (Adams
  // 1995): the normal force at t = 0.2 came out 1.4 to 5.5 times m g cos
  // theta, changing with the step and not settling as it shrank, so the
  // rigid block's closed form is no reference for it.
  check_incline<2>(20, 0.5, explicit_steps);
  check_incline<3>(20, 0.5, explicit_steps);
  return exit_status();
}
