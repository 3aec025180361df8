// Coulomb friction against a rigid obstacle (contact/penalty_contact.h,
// augmented Lagrangian) on the closed form of a block on an incline: a
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

#include <tissuefem/base/application.h>

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

  template <int dim>
  Outcome
  run(const double theta_degrees, const double mu)
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
        set Gravity = )"
         << 9.81 * std::sin(theta) << ", " << -9.81 * std::cos(theta) << zero
         << R"(
      end
      subsection Contact
        set Method        = augmented Lagrangian
        set Gap tolerance = 1e-9
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
        set Integrator = backward Euler
        set End time   = 0.2
        set Time step  = 0.01
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
  check_incline(const double theta_degrees, const double mu)
  {
    const double theta = theta_degrees * M_PI / 180, g = 9.81, dt = 0.01;
    const double mass = dim == 3 ? 0.125 : 0.25;
    // Backward Euler from rest under a constant acceleration a: x_20.
    const auto discrete
      = [&](const double a) { return a * dt * dt * 20 * 21 / 2; };
    const Outcome      frictionless = run<dim>(theta_degrees, 0);
    const Outcome      with         = run<dim>(theta_degrees, mu);
    std::ostringstream label;
    label << dim << "D, theta = " << theta_degrees << " degrees, mu = " << mu;
    const std::string name = label.str();
    check_small(frictionless.mean_x / discrete(g * std::sin(theta)) - 1,
                1e-4,
                name + ": frictionless, slides with g sin theta");
    check_small(with.normal / (mass * g * std::cos(theta)) - 1,
                1e-4,
                name + ": normal force m g cos theta");
    if (std::tan(theta) <= mu)
      {
        check_small(with.mean_x / frictionless.mean_x,
                    1e-4,
                    name + ": sticks (displacement over the frictionless one)");
        check_small(with.tangential / (mass * g * std::sin(theta)) + 1,
                    1e-4,
                    name + ": friction balances m g sin theta");
      }
    else
      {
        const double a = g * (std::sin(theta) - mu * std::cos(theta));
        check_small(with.mean_x / discrete(a) - 1,
                    1e-4,
                    name + ": slides with g (sin theta - mu cos theta)");
        check_small(with.tangential / with.normal + mu,
                    1e-6,
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
  check_incline<2>(20, 0.5);
  check_incline<2>(35, 0.5);
  check_incline<3>(20, 0.5);
  check_incline<3>(35, 0.5);
  return exit_status();
}
