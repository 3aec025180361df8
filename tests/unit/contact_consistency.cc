// Contact with rigid obstacles (contact/penalty_contact.h) is a force with a
// potential: its residual must be the gradient of implicit_energy() and its
// Jacobian the derivative of the residual, curvature term included, for
// Newton's quadratic convergence. Checked against central differences along
// random directions, on states where a sphere and a half-space both push
// into the boundary (several points in contact, others free), in 2D and
// 3D, on Q1, P1 and Q2 cells.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/base/application.h>

#include "../tests.h"
#include "solid_scene.h"

using namespace dealii;
using namespace tissuefem;

namespace
{
  std::string
  scene(const int dim, const std::string &cells, const int degree)
  {
    return "set Dimension = " + std::to_string(dim) + R"(
    subsection Geometry
      set Cell type    = )"
           + cells + R"(
      set Lower corner = 0, 0, 0
      set Upper corner = 2, 1, 1
      set Subdivisions = 4, 2, 2
    end
    subsection Finite element
      set Polynomial degree = )"
           + std::to_string(degree) + R"(
    end
    subsection Materials
      set Model           = neo-Hookean
      set Young's modulus = 10
      set Poisson's ratio = 0.3
    end
    subsection Contact
      set Penalty factor = 30
      subsection Obstacle 1
        set Shape  = sphere
        set Name   = probe
        set Motion = 0.1 * t; -0.2 * t; 0
        subsection sphere
          set Centre = 0.9, 1.35, 0.5
          set Radius = 0.5
        end
      end
      subsection Obstacle 3
        set Shape = half-space
        set Name  = floor
        subsection half-space
          set Point  = 0, 0.05, 0
          set Normal = 0.2, 1, 0.1
        end
      end
    end
    subsection Time integration
      set Integrator = backward Euler
    end
  )";
  }

  template <int dim>
  void
  check(const std::string &name, const std::string &text)
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string(text);
    tissuefem_tests::SolidScene<dim> scene(prm);
    auto                            &solid = *scene.solid;
    tissuefem_tests::Random          random(20261126);
    VectorType                       u, u_tilde, d, r, r_plus, r_minus, Jd;
    solid.initialize_vector(u);
    solid.initialize_vector(u_tilde);
    solid.initialize_vector(d);
    for (const auto i : u.locally_owned_elements())
      {
        u[i]       = 0.03 * random.uniform();
        u_tilde[i] = 0.01 * random.uniform();
        d[i]       = random.uniform();
      }
    const double c = 3., t = 0.7, h = 1e-6;
    // Contact is active: some points of both obstacles penetrate. (One
    // process: u's entries are all owned, as report() reads them.)
    const auto reports = scene.obstacle_contact->report(u, t);
    for (const auto &report : reports)
      tissuefem_tests::check(report.area > 0 && report.penetration > 0,
                             name + ": obstacle " + report.name
                               + " touches the tissue",
                             "area " + std::to_string(report.area));

    solid.implicit_residual(u, u_tilde, c, t, r, true);
    Jd.reinit(u);
    solid.jacobian().vmult(Jd, d);
    VectorType x(u);
    x.add(h, d);
    const double e_plus = solid.implicit_energy(x, u_tilde, c, t);
    solid.implicit_residual(x, u_tilde, c, t, r_plus, false);
    x.add(-2 * h, d);
    const double e_minus = solid.implicit_energy(x, u_tilde, c, t);
    solid.implicit_residual(x, u_tilde, c, t, r_minus, false);

    const double slope = r * d;
    tissuefem_tests::check_small(std::abs((e_plus - e_minus) / (2 * h) - slope)
                                   / std::abs(slope),
                                 1e-6,
                                 name + ": residual . d against dE/dd");
    r_plus -= r_minus;
    r_plus /= 2 * h;
    r_plus -= Jd;
    tissuefem_tests::check_small(r_plus.l2_norm() / Jd.l2_norm(),
                                 1e-6,
                                 name + ": J d against dR/dd");
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check<2>("Q1, 2D", scene(2, "hypercube", 1));
  check<2>("Q2, 2D", scene(2, "hypercube", 2));
  check<2>("P1, 2D", scene(2, "simplex", 1));
  check<3>("Q1, 3D", scene(3, "hypercube", 1));
  check<3>("P1, 3D", scene(3, "simplex", 1));
  return tissuefem_tests::exit_status();
}
