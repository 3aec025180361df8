// 'Finite element/Mass = lumped' (the row-sum lumped mass of the implicit
// integrators, SOFA's DiagonalMass).
//
// Operators, on every path that adds inertia (the lean P1 kernel, the
// general quadrature loop on P1, Q1 and Q2, the nodal dilatation's and the
// nodal pressure's systems, the mean dilatation): with a clamped face and
// random u, u_tilde, the implicit residual with mass coefficient c = 3
// minus the one with c = 0 must be c m (u - u_tilde) on the free rows and
// zero on the clamped ones, and the Jacobians' difference c diag(m) on the
// free rows, where m_i = int rho N_i dV is integrated here by FEValues of
// the test's own (independent of the solid's caches and kernels); the
// kinetic energy must be 1/2 sum m v^2 and the implicit energy's
// difference c/2 sum m (u - u_tilde)^2. Relative differences below 1e-12.
// The same difference with the consistent mass (the default) must miss c m
// (u - u_tilde) by more than 1 %, so that the check tells the two apart.
//
// Integrators: on the single degree of freedom of the order tests (a bar
// of one linear element, m u'' + k u = 0 with k = 1, m = 1/2 lumped and
// 1/3 consistent, from u = 0.01 at rest), backward Euler, the linearly
// implicit Euler and the quasi-Newton backward Euler must reproduce the
// backward-Euler recursion of that oscillator, (m + h^2 k) v_{n+1} = m v_n
// - h k u_n, u_{n+1} = u_n + h v_{n+1}, computed here, to 1e-9 relative
// after 50 steps of 0.02, with each mass.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/fe/fe_values.h>

#include <tissuefem/adaptation/mesh_adaptation.h>
#include <tissuefem/app/parameters.h>

#include "../tests.h"
#include "solid_scene.h"

#include <cmath>
#include <iostream>
#include <map>
#include <sstream>

using namespace dealii;
using namespace tissuefem;

namespace
{
  constexpr double rho = 2.;

  std::string
  scene(const int          dim,
        const std::string &cells,
        const unsigned int degree,
        const std::string &kernel,
        const std::string &formulation,
        const std::string &mass)
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
      set Element kernel    = )"
           + kernel + R"(
      set Mass              = )"
           + mass + R"(
    end
    subsection Materials
      set Formulation     = )"
           + formulation + R"(
      set Model           = neo-Hookean
      set Young's modulus = 10
      set Poisson's ratio = 0.45
      set Density         = )"
           + std::to_string(rho) + R"(
    end
    subsection Boundary conditions
      set Dirichlet = 0: )"
           + std::string(dim == 2 ? "xy: 0; 0" : "xyz: 0; 0; 0") + R"(
      set Gravity = 0, -1, 0.5
    end
    subsection Linear solver
      set Type = MUMPS
    end
  )";
  }

  /// int rho N_i dV for every dof, by FEValues on the scene's numbering.
  template <int dim>
  Vector<double>
  row_sums(const solid::Discretization<dim> &discretization)
  {
    Vector<double>                       m(discretization.n_dofs());
    const auto                          &fe = *discretization.fe;
    FEValues<dim>                        fe_values(*discretization.mapping,
                            fe,
                            discretization.cell_quadrature,
                            update_values | update_JxW_values);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : discretization.dof_handler.active_cell_iterators())
      {
        fe_values.reinit(cell);
        cell->get_dof_indices(dofs);
        for (unsigned int i = 0; i < dofs.size(); ++i)
          for (unsigned int q = 0; q < fe_values.n_quadrature_points; ++q)
            m[dofs[i]] += rho * fe_values.shape_value(i, q) * fe_values.JxW(q);
      }
    return m;
  }

  FullMatrix<double>
  dense(const MatrixType &matrix, const unsigned int n)
  {
    FullMatrix<double> result(n, n);
    for (const auto &entry : matrix)
      result(entry.row(), entry.column()) = entry.value();
    return result;
  }

  /// Checks the lumped operators of one scene; returns the relative miss
  /// of the residual difference against c m (u - u_tilde) (for the
  /// consistent mass, where it must be large).
  template <int dim>
  double
  check_scene(const std::string &text,
              const std::string &name,
              const bool         lumped,
              const bool         own_system = false)
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string(text);
    tissuefem_tests::SolidScene<dim> scene(prm);
    auto                            &solid = *scene.solid;
    // The nodal dilatation's own Newton system takes the inertia into its
    // cell blocks (NodalDilatationSystem::add_loads): its residual is
    // checked, its matrix is not the solid's.
    if (own_system)
      solid.solve_only_through_operators(true, *scene.linear_solver);
    const auto             &disc = *scene.discretization;
    tissuefem_tests::Random random(20261129);
    VectorType              u, u_tilde, r_c, r_0;
    solid.initialize_vector(u);
    solid.initialize_vector(u_tilde);
    for (const auto i : u.locally_owned_elements())
      {
        u[i]       = 0.03 * random.uniform();
        u_tilde[i] = 0.05 * random.uniform();
      }
    solid.apply_dirichlet_values(0., u);
    const double c = 3.;
    const auto   n = solid.n_dofs();
    // The nodal pressure's Jacobian is its own system's (the displacement
    // block's inertia comes from the lean kernel, checked on P1).
    const bool with_jacobian
      = prm.get({"Materials"}, "Formulation") != "nodal pressure"
        && !own_system;
    FullMatrix<double> J_c(n, n), J_0(n, n);
    solid.implicit_residual(
      u, u_tilde, c, 0., r_c, with_jacobian || own_system);
    if (with_jacobian)
      J_c = dense(solid.jacobian(), n);
    solid.implicit_residual(
      u, u_tilde, 0., 0., r_0, with_jacobian || own_system);
    if (with_jacobian)
      J_0 = dense(solid.jacobian(), n);
    const Vector<double> m = row_sums(disc);

    // Expected differences: c m (u - u_tilde) and c diag(m) on free rows.
    Vector<double>     miss(n), expected(n);
    FullMatrix<double> matrix_miss(J_c);
    matrix_miss.add(-1., J_0);
    double matrix_scale = 0;
    for (unsigned int i = 0; i < n; ++i)
      {
        const bool free = !disc.constraints.is_constrained(i);
        expected[i]     = free ? c * m[i] * (u[i] - u_tilde[i]) : 0.;
        miss[i]         = r_c[i] - r_0[i] - expected[i];
        if (!free)
          for (unsigned int j = 0; j < n; ++j)
            matrix_miss(i, j) = 0;
        else
          {
            matrix_miss(i, i) -= c * m[i];
            matrix_scale += std::pow(c * m[i], 2);
          }
      }
    const double residual_miss = miss.l2_norm() / expected.l2_norm();
    if (!lumped)
      return residual_miss;
    tissuefem_tests::check_small(residual_miss,
                                 1e-12,
                                 name
                                   + ": R(c) - R(0) against c m (u - u_tilde), "
                                     "relative");
    if (with_jacobian)
      tissuefem_tests::check_small(matrix_miss.frobenius_norm()
                                     / std::sqrt(matrix_scale),
                                   1e-12,
                                   name
                                     + ": J(c) - J(0) against c diag(m), "
                                       "relative");

    double kinetic = 0, inertial = 0;
    for (unsigned int i = 0; i < n; ++i)
      {
        kinetic += 0.5 * m[i] * u_tilde[i] * u_tilde[i];
        inertial += 0.5 * c * m[i] * std::pow(u[i] - u_tilde[i], 2);
      }
    tissuefem_tests::check_small(solid.kinetic_energy(u_tilde) / kinetic - 1,
                                 1e-12,
                                 name
                                   + ": kinetic energy against 1/2 sum m "
                                     "v^2, relative");
    const double energy_difference = solid.implicit_energy(u, u_tilde, c, 0.)
                                     - solid.implicit_energy(u, u_tilde, 0, 0.);
    tissuefem_tests::check_small(energy_difference / inertial - 1,
                                 1e-10,
                                 name
                                   + ": implicit energy's inertial part "
                                     "against c/2 sum m (u - u_tilde)^2, "
                                     "relative");
    return residual_miss;
  }

  template <int dim>
  void
  check_path(const std::string &cells,
             const unsigned int degree,
             const std::string &kernel,
             const std::string &formulation,
             const std::string &label,
             const bool         own_system = false)
  {
    const std::string name = std::to_string(dim) + "D " + label;
    check_scene<dim>(scene(dim, cells, degree, kernel, formulation, "lumped"),
                     name,
                     true,
                     own_system);
    const double consistent_miss = check_scene<dim>(
      scene(dim, cells, degree, kernel, formulation, "consistent"),
      name,
      false,
      own_system);
    tissuefem_tests::check(consistent_miss > 0.01,
                           name
                             + ": the consistent mass's difference misses "
                               "c m (u - u_tilde) by more than 1 %",
                           "relative miss " + std::to_string(consistent_miss));
  }


  /**
   * On a mesh with hanging nodes (Q1, a third of the cells refined once)
   * with @p mass: the implicit residual is the derivative of the implicit
   * energy and the Jacobian the residual's, at a state whose hanging-node
   * values are stale (Newton leaves them so) along a direction that is
   * zero on them (as Newton's updates are): the inertia must follow the
   * parents' values in both.
   */
  void
  check_hanging_nodes(const std::string &mass)
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string(
      scene(2, "hypercube", 1, "automatic", "displacement", mass) + R"(
    subsection Mesh refinement
      set Indicator       = Kelly
      set Refine fraction = 0.3
      set Maximum levels  = 1
    end
  )");
    tissuefem_tests::SolidScene<2> scene(prm);
    auto                          &solid      = *scene.solid;
    const auto                     adaptation = scene.mesh_adaptation(prm);
    tissuefem_tests::Random        random(20261130);
    VectorType                     u, u_tilde, d;
    solid.initialize_vector(u);
    for (const auto i : u.locally_owned_elements())
      u[i] = 0.03 * random.uniform() * (1 + i % 3);
    adaptation->adapt(u, 0., 0.05, {&u});
    const std::string name = "2D Q1 with hanging nodes, " + mass + " mass";
    tissuefem_tests::check(solid.has_hanging_nodes(),
                           name + ": the mesh has hanging nodes",
                           "none");
    solid.initialize_vector(u);
    solid.initialize_vector(u_tilde);
    solid.initialize_vector(d);
    for (const auto i : u.locally_owned_elements())
      {
        u[i]       = 0.03 * random.uniform();
        u_tilde[i] = 0.05 * random.uniform();
        d[i]       = random.uniform() - 0.5;
      }
    solid.apply_dirichlet_values(0., u);
    const auto &hanging = scene.discretization->hanging_node_constraints;
    for (const auto i : u.locally_owned_elements())
      if (hanging.is_constrained(i))
        u[i] += 0.02;
    solid.zero_constrained_entries(d);
    tissuefem_tests::check_derivatives(solid, u, u_tilde, 3., 0., d, name);
  }

  void
  check_integrators()
  {
    for (const std::string mass : {"lumped", "consistent"})
      for (const std::string integrator : {"backward Euler",
                                           "linearly implicit Euler",
                                           "quasi-Newton backward Euler"})
        {
          ParameterHandler prm;
          declare_all_parameters(prm);
          prm.parse_input_from_string(
            tissuefem_tests::one_element_bar("set Integrator = " + integrator
                                             + "\n")
            + "subsection Finite element\n set Mass = " + mass + "\nend\n");
          Vector<double> final_u;
          {
            const tissuefem_tests::Muted muted;
            tissuefem_tests::run_to_end<1>(prm, 0.02, 1., &final_u);
          }
          const double expected
            = tissuefem_tests::one_element_bar_backward_euler(
              mass == "lumped" ? 0.5 : 1. / 3);
          tissuefem_tests::check_small(
            (final_u[final_u.size() - 1] - expected) / expected,
            1e-9,
            integrator + ", " + mass
              + " mass: u(1) against the oscillator's backward-Euler "
                "recursion, relative");
        }
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check_path<2>("simplex", 1, "automatic", "displacement", "P1 lean kernel");
  check_path<3>("simplex", 1, "automatic", "displacement", "P1 lean kernel");
  check_path<3>("simplex", 1, "general", "displacement", "P1 general loop");
  check_path<2>("hypercube", 1, "automatic", "displacement", "Q1");
  check_path<3>("hypercube", 1, "automatic", "displacement", "Q1");
  check_path<3>("hypercube", 2, "automatic", "displacement", "Q2");
  check_path<3>(
    "simplex", 1, "automatic", "nodal dilatation", "P1 nodal dilatation");
  check_path<3>(
    "simplex", 1, "automatic", "nodal pressure", "P1 nodal pressure");
  check_path<3>("simplex",
                1,
                "automatic",
                "nodal dilatation",
                "P1 nodal dilatation, own system",
                true);
  check_path<2>(
    "hypercube", 1, "automatic", "mean dilatation", "Q1 mean dilatation");
  check_hanging_nodes("lumped");
  check_hanging_nodes("consistent");
  check_integrators();
  return tissuefem_tests::exit_status();
}
