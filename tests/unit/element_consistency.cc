// The residual is the gradient of implicit_energy() and the Jacobian the
// derivative of the residual, for the formulations whose elements couple
// quadrature points or need a custom tangent: the mean dilatation (F-bar)
// element on Q1 and Q2 quadrilaterals, Q1 hexahedra and P2 tetrahedra, the
// nodal dilatation element on P1 triangles and tetrahedra (whose cells
// couple through the patches around their vertices), and
// the invertible neo-Hookean model on states with inverted and collapsed
// cells. Checked against central differences along random directions (the
// energy line search relies on the first, Newton's quadratic convergence on
// the second). With 'Tangent projection = positive definite' the Jacobian
// of a badly inverted state must be positive semi-definite.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/app/parameters.h>
#include <tissuefem/solid/mean_dilatation.h>

#include "../tests.h"
#include "solid_scene.h"

using namespace dealii;
using namespace tissuefem;

namespace
{
  std::string
  scene(const int          dim,
        const std::string &cells,
        const int          degree,
        const std::string &model,
        const std::string &formulation,
        const std::string &projection)
  {
    return "set Dimension = " + std::to_string(dim) + R"(
    subsection Geometry
      set Cell type    = )"
           + cells + R"(
      set Lower corner = 0, 0, 0
      set Upper corner = 2, 1, 1
      set Subdivisions = 3, 2, 2
    end
    subsection Finite element
      set Polynomial degree = )"
           + std::to_string(degree) + R"(
    end
    subsection Materials
      set Model              = )"
           + model + R"(
      set Young's modulus    = 10
      set Poisson's ratio    = 0.45
      set Density            = 2
      set Formulation        = )"
           + formulation + R"(
      set Tangent projection = )"
           + projection + R"(
    end
    subsection Boundary conditions
      set Neumann = )"
           + std::string(dim == 2 ? "1: 0.3; -0.2" : "1: 0.3; -0.2; 0.1") + R"(
      set Gravity = 0, -1, 0.5
    end
  )";
  }

  template <int dim>
  void
  check(const std::string &name,
        const std::string &text,
        const double       amplitude,
        const bool         check_definite)
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string(text);
    tissuefem_tests::SolidScene<dim> scene(prm);
    auto                            &solid = *scene.solid;
    tissuefem_tests::Random          random(20261123);
    VectorType                       u, u_tilde, d, Jd;
    solid.initialize_vector(u);
    solid.initialize_vector(u_tilde);
    solid.initialize_vector(d);
    for (const auto i : u.locally_owned_elements())
      {
        u[i]       = amplitude * random.uniform();
        u_tilde[i] = 0.05 * random.uniform();
        d[i]       = random.uniform();
      }
    // (A projected tangent is no derivative.)
    tissuefem_tests::check_derivatives(
      solid, u, u_tilde, 3., 0.7, d, name, !check_definite);
    if (check_definite)
      {
        // d^T J d >= 0 for every random direction.
        double smallest = 1e300, largest = 0;
        for (unsigned int k = 0; k < 20; ++k)
          {
            for (const auto i : d.locally_owned_elements())
              d[i] = random.uniform();
            Jd.reinit(d);
            solid.jacobian().vmult(Jd, d);
            tissuefem_tests::lower(smallest, (Jd * d) / (d * d));
            tissuefem_tests::raise(largest, (Jd * d) / (d * d));
          }
        tissuefem_tests::check(smallest >= -1e-12 * largest,
                               name
                                 + ": projected Jacobian is positive "
                                   "semi-definite on 20 directions",
                               "smallest Rayleigh quotient "
                                 + std::to_string(smallest) + ", largest "
                                 + std::to_string(largest));
      }
  }

  /// The closed-form derivatives of phi(F, theta) = Psi(Fbar) against
  /// nested AD through the map (F, theta) -> Fbar, for random F near the
  /// identity, theta, Pbar and Abar (with the major symmetry of every
  /// second derivative, A_ijkl = A_klij, which the AD version assumes).
  template <int dim>
  void
  check_dilatation_chain()
  {
    tissuefem_tests::Random random(20261127 + dim);
    double                  worst = 0;
    for (unsigned int trial = 0; trial < 20; ++trial)
      {
        Tensor<2, dim> F, P;
        Tensor<4, dim> A;
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            {
              F[i][j] = (i == j) + 0.3 * random.uniform();
              P[i][j] = random.uniform();
              for (unsigned int k = 0; k < dim; ++k)
                for (unsigned int l = 0; l < dim; ++l)
                  A[i][j][k][l] = random.uniform();
            }
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            for (unsigned int k = 0; k < dim; ++k)
              for (unsigned int l = 0; l < dim; ++l)
                if (std::make_pair(k, l) < std::make_pair(i, j))
                  A[i][j][k][l] = A[k][l][i][j];
        const double theta = determinant(F) * (1 + 0.2 * random.uniform());
        solid::MeanDilatationPoint<dim> closed, ad;
        solid::mean_dilatation_stress_and_tangent(F, theta, P, A, closed);
        solid::mean_dilatation_stress_and_tangent_by_ad(F, theta, P, A, ad);
        const auto relative = [](const auto &a, const auto &b) {
          return (a - b).norm() / std::max(1e-300, b.norm());
        };
        tissuefem_tests::raise(worst, relative(closed.phi_F, ad.phi_F));
        tissuefem_tests::raise(worst, relative(closed.phi_FF, ad.phi_FF));
        tissuefem_tests::raise(worst,
                               relative(closed.phi_F_theta, ad.phi_F_theta));
        tissuefem_tests::raise(worst,
                               std::abs(closed.phi_theta - ad.phi_theta)
                                 / std::abs(ad.phi_theta));
        tissuefem_tests::raise(worst,
                               std::abs(closed.phi_theta_theta
                                        - ad.phi_theta_theta)
                                 / std::abs(ad.phi_theta_theta));
      }
    tissuefem_tests::check_small(worst,
                                 1e-12,
                                 "F-bar chain rule in closed form against "
                                 "nested AD, "
                                   + std::to_string(dim)
                                   + "D, 20 random states");
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check_dilatation_chain<2>();
  check_dilatation_chain<3>();
  const std::string md = "mean dilatation", plain = "displacement";
  check<2>("F-bar Q1, 2D",
           scene(2, "hypercube", 1, "neo-Hookean", md, "none"),
           0.1,
           false);
  check<2>("F-bar Q2, 2D",
           scene(2, "hypercube", 2, "neo-Hookean", md, "none"),
           0.05,
           false);
  check<3>("F-bar Q1, 3D",
           scene(3, "hypercube", 1, "robust neo-Hookean", md, "none"),
           0.1,
           false);
  check<3>("F-bar P2 tetrahedra",
           scene(3, "simplex", 2, "St Venant-Kirchhoff", md, "none"),
           0.05,
           false);
  const std::string nodal = "nodal dilatation";
  check<2>("nodal dilatation P1 triangles",
           scene(2, "simplex", 1, "neo-Hookean", nodal, "none"),
           0.1,
           false);
  check<3>("nodal dilatation P1 tetrahedra",
           scene(3, "simplex", 1, "robust neo-Hookean", nodal, "none"),
           0.1,
           false);
  check<3>("nodal dilatation P1 tetrahedra, St Venant-Kirchhoff",
           scene(3, "simplex", 1, "St Venant-Kirchhoff", nodal, "none"),
           0.05,
           false);
  check<2>("invertible neo-Hookean, inverted, 2D",
           scene(2, "hypercube", 1, "invertible neo-Hookean", plain, "none"),
           1.5,
           false);
  check<3>("invertible neo-Hookean, inverted, 3D",
           scene(3, "simplex", 1, "invertible neo-Hookean", plain, "none"),
           1.5,
           false);
  check<3>(
    "invertible neo-Hookean, projected tangent",
    scene(
      3, "simplex", 1, "invertible neo-Hookean", plain, "positive definite"),
    1.5,
    true);
  return tissuefem_tests::exit_status();
}
