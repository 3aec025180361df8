// The four-unknown linear simplex ('Formulation = nodal pressure',
// solid/nodal_pressure.h) against what it must be, independently of its
// own code:
// - on a homogeneous deformation the pressure solving A p = b(u) is lambda
//   g(J) at every vertex (constants are in the stabilization's kernel), so
//   its energy and residual are plain P1's ('displacement'), for a random
//   affine map;
// - on random states, the residual is the gradient of its energy
//   (central differences along a random direction: the line search relies
//   on it), and the update its Newton system gives for the central
//   difference of the residual along d is d (the system's elimination of
//   the pressure is the exact tangent, Newton's quadratic convergence);
// - the lifted update meets the Dirichlet values exactly;
// on P1 triangles and tetrahedra, neo-Hookean and robust neo-Hookean, with
// MUMPS, KLU and UMFPACK (one process), on 1 and 2 processes. Figures are
// relative differences.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>

#include <tissuefem/app/parameters.h>
#include <tissuefem/solid/quantities.h>

#include "../tests.h"
#include "solid_scene.h"

#include <cmath>
#include <map>

using namespace dealii;
using namespace tissuefem;

namespace
{
  std::string
  scene(const int          dim,
        const std::string &model,
        const std::string &solver,
        const std::string &formulation,
        const bool         clamped = true)
  {
    const std::string clamp = dim == 2 ? "xy: 0; 0" : "xyz: 0; 0; 0";
    // The left end clamped, the right end moved at time 1 (so that the
    // lifting has an increment to carry), gravity.
    return "set Dimension = " + std::to_string(dim) + R"(
    subsection Geometry
      set Cell type    = simplex
      set Lower corner = 0, 0, 0
      set Upper corner = 2, 1, 1
      set Subdivisions = 4, 3, 2
    end
    subsection Materials
      set Model           = )"
           + model + R"(
      set Young's modulus = 10
      set Poisson's ratio = 0.499
      set Density         = 2
      set Formulation     = )"
           + formulation + R"(
    end
    subsection Linear solver
      set Type = )"
           + solver + R"(
    end
    subsection Boundary conditions
      set Dirichlet = )"
           + (clamped ? "0: " + clamp + " | 1: x: 0.1 * t" : "") + R"(
      set Gravity   = 0, -1, 0.5
    end
  )";
  }

  double
  relative(const VectorType &a, const VectorType &b)
  {
    VectorType difference(a);
    difference -= b;
    return difference.l2_norm() / b.l2_norm();
  }

  /// The energy and residual of the affine map u = G X under both
  /// formulations (no Dirichlet values: the residual's every row).
  template <int dim>
  void
  check_homogeneous(const std::string &model)
  {
    tissuefem_tests::Random random(20261129);
    Tensor<2, dim>          G;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        G[i][j] = 0.15 * random.uniform();
    std::array<double, 2>     energy;
    std::array<VectorType, 2> residual;
    for (unsigned int f = 0; f < 2; ++f)
      {
        ParameterHandler prm;
        declare_all_parameters(prm);
        prm.parse_input_from_string(
          scene(dim,
                model,
                "MUMPS",
                f == 0 ? "displacement" : "nodal pressure",
                false));
        tissuefem_tests::SolidScene<dim> scene(prm);
        auto                            &solid = *scene.solid;
        VectorType                       u, u_tilde;
        solid.initialize_vector(u);
        solid.initialize_vector(u_tilde);
        std::map<types::global_dof_index, Point<dim>> points;
        DoFTools::map_dofs_to_support_points(*scene.discretization->mapping,
                                             scene.discretization->dof_handler,
                                             points);
        // A P1 vertex's dofs are its components in turn (the system's
        // layout).
        for (const auto i : u.locally_owned_elements())
          u[i] = (G * points.at(i))[i % dim];
        u.compress(VectorOperation::insert);
        energy[f] = solid.implicit_energy(u, u_tilde, 3., 0.);
        solid.implicit_residual(u, u_tilde, 3., 0., residual[f], false);
      }
    tissuefem_tests::check_small(std::abs(energy[1] - energy[0])
                                   / std::abs(energy[0]),
                                 1e-12,
                                 model + ", " + std::to_string(dim)
                                   + "D: a homogeneous state's energy is "
                                     "plain P1's");
    tissuefem_tests::check_small(relative(residual[1], residual[0]),
                                 1e-10,
                                 model + ", " + std::to_string(dim)
                                   + "D: a homogeneous state's residual is "
                                     "plain P1's");
  }

  /**
   * The stored energy of a random state against an evaluation of its own:
   * the pressure's mass M and cell-mean part M0 integrated by FEValues
   * (exact for quadratics) instead of in closed form, A = M / lambda +
   * alpha (M - M0) / mu and b_i = int N_i log J assembled densely, and W =
   * int (mu/2 (tr F^T F - d) - mu log J) + b^T A^{-1} b / 2 (the
   * neo-Hookean energy with its lambda/2 log^2 J replaced).
   */
  template <int dim>
  void
  check_energy()
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string(
      scene(dim, "neo-Hookean", "MUMPS", "nodal pressure", false));
    tissuefem_tests::SolidScene<dim> scene(prm);
    const auto                      &d = *scene.discretization;
    tissuefem_tests::Random          random(20261130);
    VectorType                       u;
    scene.solid->initialize_vector(u);
    for (const auto i : u.locally_owned_elements())
      u[i] = 0.1 * random.uniform();
    u.compress(VectorOperation::insert);
    VectorType ghosted(d.locally_owned, d.locally_relevant, MPI_COMM_WORLD);
    ghosted = u;

    const double E = 10, nu = 0.499, alpha = 4; // the scene's, the default
    const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
    const double mu     = E / (2 * (1 + nu));
    const unsigned int                   n_v = d.dof_handler.n_dofs() / dim;
    std::vector<double>                  A(n_v * n_v, 0.), b(n_v, 0.);
    double                               rest = 0;
    const QGaussSimplex<dim>             quadrature(2);
    FEValues<dim>                        fe_values(*d.mapping,
                            *d.fe,
                            quadrature,
                            update_values | update_gradients
                              | update_JxW_values);
    const FEValuesExtractors::Vector     displacement(0);
    std::vector<Tensor<2, dim>>          grad(quadrature.size());
    std::vector<types::global_dof_index> dofs(d.fe->n_dofs_per_cell());
    struct Cell
    {
      unsigned int              index;
      Tensor<2, dim>            F;
      std::vector<unsigned int> vertex;
    };
    std::vector<Cell> cells;
    for (const auto &cell : d.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[displacement].get_function_gradients(ghosted, grad);
          cell->get_dof_indices(dofs);
          // The hat functions: the first component's shape functions; a
          // vertex's pressure index is that dof / dim.
          std::vector<unsigned int> hat, vertex;
          for (unsigned int k = 0; k < dofs.size(); ++k)
            if (d.fe->system_to_component_index(k).first == 0)
              {
                hat.push_back(k);
                vertex.push_back(dofs[k] / dim);
              }
          const Tensor<2, dim> F = unit_symmetric_tensor<dim>() + grad[0];
          const double         J = determinant(F);
          cells.push_back({cell->active_cell_index(), F, vertex});
          double              V = 0;
          std::vector<double> mean(hat.size(), 0.);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              V += fe_values.JxW(q);
              for (unsigned int a = 0; a < hat.size(); ++a)
                mean[a] += fe_values.shape_value(hat[a], q) * fe_values.JxW(q);
            }
          rest
            += V * (0.5 * mu * (scalar_product(F, F) - dim) - mu * std::log(J));
          for (unsigned int a = 0; a < hat.size(); ++a)
            {
              b[vertex[a]] += mean[a] * std::log(J);
              for (unsigned int c = 0; c < hat.size(); ++c)
                {
                  double m = 0;
                  for (unsigned int q = 0; q < quadrature.size(); ++q)
                    m += fe_values.shape_value(hat[a], q)
                         * fe_values.shape_value(hat[c], q) * fe_values.JxW(q);
                  const double m0 = mean[a] * mean[c] / V;
                  A[vertex[a] * n_v + vertex[c]]
                    += m / lambda + alpha * (m - m0) / mu;
                }
            }
        }
    Utilities::MPI::sum(A, MPI_COMM_WORLD, A);
    Utilities::MPI::sum(b, MPI_COMM_WORLD, b);
    rest = Utilities::MPI::sum(rest, MPI_COMM_WORLD);
    FullMatrix<double> dense(n_v, n_v);
    for (unsigned int i = 0; i < n_v; ++i)
      for (unsigned int j = 0; j < n_v; ++j)
        dense(i, j) = A[i * n_v + j];
    dense.gauss_jordan();
    Vector<double> rhs(b.begin(), b.end()), p(n_v);
    dense.vmult(p, rhs);
    const double expected = rest + 0.5 * (p * rhs);
    const double energy   = scene.solid->stored_energy(u);
    // The outputs' von Mises stress with the cell's own pressure pbar (the
    // mean of its vertices'): P = mu F + (pbar - mu) F^{-T}, sigma = P F^T / J.
    Vector<float> jacobian, von_mises;
    solid::cell_fields(d,
                       scene.solid->get_materials(),
                       scene.solid->fibres(),
                       scene.solid->deformation(ghosted).get(),
                       ghosted,
                       jacobian,
                       von_mises);
    double worst = 0;
    for (const auto &cell : cells)
      {
        double pbar = 0;
        for (const unsigned int v : cell.vertex)
          pbar += p[v] / cell.vertex.size();
        const double         J = determinant(cell.F);
        const Tensor<2, dim> P
          = mu * cell.F + (pbar - mu) * transpose(invert(cell.F));
        const Tensor<2, dim> sigma    = P * transpose(cell.F) / J;
        Tensor<2, dim>       deviator = sigma;
        for (unsigned int i = 0; i < dim; ++i)
          deviator[i][i] -= trace(sigma) / dim;
        const double expected_vm
          = std::sqrt(1.5 * scalar_product(deviator, deviator));
        tissuefem_tests::raise(worst,
                               std::abs(von_mises[cell.index] - expected_vm)
                                 / expected_vm);
      }
    worst = Utilities::MPI::max(worst, MPI_COMM_WORLD);
    tissuefem_tests::check_small(worst,
                                 1e-5,
                                 std::to_string(dim)
                                   + "D: the outputs' von Mises stress with "
                                     "the cells' own pressures (single "
                                     "precision)");
    tissuefem_tests::check_small(std::abs(energy - expected)
                                   / std::abs(expected),
                                 1e-10,
                                 std::to_string(dim)
                                   + "D: a random state's energy against "
                                     "A and b integrated on their own");
  }

  template <int dim>
  void
  check(const std::string &name, const std::string &text)
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string(text);
    tissuefem_tests::SolidScene<dim> scene(prm);
    auto                            &solid  = *scene.solid;
    auto                            &solver = *scene.linear_solver;
    tissuefem_tests::Random          random(20261129);
    VectorType                       u, u_tilde, d;
    solid.initialize_vector(u);
    solid.initialize_vector(u_tilde);
    solid.initialize_vector(d);
    for (const auto i : u.locally_owned_elements())
      {
        u[i]       = 0.1 * random.uniform();
        u_tilde[i] = 0.05 * random.uniform();
        d[i]       = random.uniform();
      }
    solid.apply_dirichlet_values(0., u);
    // d vanishes where the Dirichlet values hold: the Newton rows.
    solid.apply_dirichlet_values(0., d);
    VectorType zero(d);
    zero = 0;
    solid.apply_dirichlet_values(0., zero);
    d -= zero;
    const double c = 3., t = 0.;
    solid.solve_only_through_operators(true, solver);

    const double h = 1e-6;
    VectorType   r, r_plus, r_minus, x(u), update;
    solid.initialize_vector(update);
    solid.implicit_residual(u, u_tilde, c, t, r, true);
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
    // K^{-1} (dR/dd) = d.
    r_plus -= r_minus;
    r_plus /= 2 * h;
    solid.implicit_residual(u, u_tilde, c, t, r, true);
    solid.solve_jacobian(solver, update, r_plus, true, 0.);
    tissuefem_tests::check_small(relative(update, d),
                                 1e-6,
                                 name + ": the system's update for dR/dd is d");

    // The lifted update meets the right end's 0.1 at t = 1.
    VectorType lifted, b;
    solid.initialize_vector(lifted);
    solid.implicit_residual_lifting(u, u_tilde, c, 1., lifted, true);
    b = lifted;
    b *= -1.;
    solid.solve_jacobian(solver, update, b, true, 0.);
    VectorType moved(u), prescribed;
    moved += update;
    prescribed = moved;
    solid.apply_dirichlet_values(1., prescribed);
    prescribed -= moved;
    tissuefem_tests::check_small(prescribed.linfty_norm() / 0.1,
                                 1e-12,
                                 name
                                   + ": the lifted state meets the Dirichlet "
                                     "values");
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const tissuefem_tests::OneWriter one_writer;
  check_homogeneous<2>("neo-Hookean");
  check_homogeneous<3>("robust neo-Hookean");
  check_energy<2>();
  check_energy<3>();
  for (const std::string solver : {"MUMPS", "KLU", "UMFPACK"})
    {
      if (solver == "UMFPACK"
          && Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
        continue;
      check<2>("P1 triangles, neo-Hookean, " + solver,
               scene(2, "neo-Hookean", solver, "nodal pressure"));
      check<3>("P1 tetrahedra, robust neo-Hookean, " + solver,
               scene(3, "robust neo-Hookean", solver, "nodal pressure"));
    }
  return tissuefem_tests::failures() == 0 ? 0 : 1;
}
