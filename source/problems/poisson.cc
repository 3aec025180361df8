#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/numerics/vector_tools.h>

#include <tissuefem/base/parallel.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/geometry/geometry.h>
#include <tissuefem/output/output_parameters.h>
#include <tissuefem/problems/interface.h>
#include <tissuefem/solid/discretization.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace tissuefem::problems
{
  /**
   * The variable-coefficient Poisson problem of Teran's lecture notes
   * (eq 2.1): -div(beta grad u) = f, u = p on Dirichlet boundaries,
   * beta grad u . n = q on Neumann boundaries, solved on a sequence of
   * uniformly refined meshes. With an exact solution it prints the L2 and H1
   * seminorm errors and their convergence rates (log2 of successive error
   * ratios): a verification of the element, quadrature and boundary
   * machinery the elasticity solver shares.
   */
  template <int dim>
  class Poisson : public Interface
  {
  public:
    Poisson(ParameterHandler &prm, const RunContext &context);

    static void
    declare_parameters(ParameterHandler &prm);

    void
    setup() override;

    void
    run() override;

  private:
    geometry::GeometryParameters         geometry_parameters;
    solid::FiniteElementParameters       fe_parameters;
    output::OutputParameters             output_parameters;
    unsigned int                         cycles;
    std::unique_ptr<FunctionParser<dim>> coefficient, rhs, exact;
    std::vector<
      std::pair<types::boundary_id, std::unique_ptr<FunctionParser<dim>>>>
      dirichlet, neumann;

    void
    solve_on(const Triangulation<dim> &triangulation,
             double                   &l2_error,
             double                   &h1_error,
             unsigned int             &n_dofs) const;
  };


  template <int dim>
  void
  Poisson<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Poisson");
    prm.declare_entry("Coefficient",
                      "1",
                      Patterns::Anything(),
                      "beta(x, y, z) > 0 in -div(beta grad u) = f.");
    prm.declare_entry("Right hand side",
                      "0",
                      Patterns::Anything(),
                      "f(x, y, z).");
    prm.declare_entry("Dirichlet",
                      "",
                      Patterns::Anything(),
                      "Entries 'id: p(x, y, z)' separated by '|': u = p on "
                      "the boundary with that id.");
    prm.declare_entry("Neumann",
                      "",
                      Patterns::Anything(),
                      "Entries 'id: q(x, y, z)' separated by '|': beta grad u "
                      ". n = q on the boundary with that id (outward normal "
                      "n). Unlisted boundaries have q = 0.");
    prm.declare_entry("Exact solution",
                      "",
                      Patterns::Anything(),
                      "u(x, y, z) if known: then errors and rates are "
                      "printed.");
    prm.declare_entry("Refinement cycles",
                      "1",
                      Patterns::Integer(1, 12),
                      "Number of meshes: the geometry's mesh, then each one "
                      "refined once more.");
    prm.leave_subsection();
  }


  namespace
  {
    template <int dim>
    std::vector<
      std::pair<types::boundary_id, std::unique_ptr<FunctionParser<dim>>>>
    parse_scalar_boundary_data(const std::string &text,
                               const std::string &parameter)
    {
      std::vector<
        std::pair<types::boundary_id, std::unique_ptr<FunctionParser<dim>>>>
        result;
      for (const auto &[id, expression] : parse_id_entries(text, parameter))
        result.emplace_back(id, make_function<dim>(expression, 1, parameter));
      return result;
    }
  } // namespace


  template <int dim>
  Poisson<dim>::Poisson(ParameterHandler &prm, const RunContext &context)
  {
    geometry_parameters.parse_parameters(prm);
    require(geometry_parameters.distribution == geometry::Distribution::shared
              || parallel_tools::n_processes() == 1,
            "Geometry/Mesh distribution",
            "'distributed' is for the elasticity problem; the Poisson problem "
            "holds the whole mesh on every process (use 'shared')");
    geometry_parameters.resolve_relative_to(context.parameter_directory);
    fe_parameters.parse_parameters(prm);
    output_parameters.parse_parameters(prm);
    prm.enter_subsection("Poisson");
    coefficient
      = make_function<dim>(prm.get("Coefficient"), 1, "Poisson/Coefficient");
    rhs = make_function<dim>(prm.get("Right hand side"),
                             1,
                             "Poisson/Right hand side");
    if (!prm.get("Exact solution").empty())
      {
        exact = make_function<dim>(prm.get("Exact solution"),
                                   1,
                                   "Poisson/Exact solution");
        // Central differences of fourth order for the H1 error's gradient.
        exact->set_formula(AutoDerivativeFunction<dim>::FourthOrder);
      }
    dirichlet = parse_scalar_boundary_data<dim>(prm.get("Dirichlet"),
                                                "Poisson/Dirichlet");
    neumann
      = parse_scalar_boundary_data<dim>(prm.get("Neumann"), "Poisson/Neumann");
    cycles = prm.get_integer("Refinement cycles");
    prm.leave_subsection();
  }


  template <int dim>
  void
  Poisson<dim>::setup()
  {
    Triangulation<dim> triangulation;
    geometry::build_triangulation(geometry_parameters, triangulation);
    const auto ids = triangulation.get_boundary_ids();
    for (const auto *list : {&dirichlet, &neumann})
      for (const auto &entry : *list)
        require(std::find(ids.begin(), ids.end(), entry.first) != ids.end(),
                list == &dirichlet ? "Poisson/Dirichlet" : "Poisson/Neumann",
                "boundary id " + std::to_string(entry.first)
                  + " is on no boundary face of the mesh");
  }


  template <int dim>
  void
  Poisson<dim>::solve_on(const Triangulation<dim> &triangulation,
                         double                   &l2_error,
                         double                   &h1_error,
                         unsigned int             &n_dofs) const
  {
    solid::Discretization<dim> d(triangulation, fe_parameters, 1);
    n_dofs = d.dof_handler.n_dofs();

    AffineConstraints<double> constraints;
    for (const auto &[id, function] : dirichlet)
      VectorTools::interpolate_boundary_values(
        *d.mapping, d.dof_handler, id, *function, constraints);
    constraints.close();

    DynamicSparsityPattern dsp(n_dofs);
    DoFTools::make_sparsity_pattern(d.dof_handler, dsp, constraints, false);
    SparsityPattern sparsity;
    sparsity.copy_from(dsp);
    SparseMatrix<double> matrix(sparsity);
    Vector<double>       solution(n_dofs), system_rhs(n_dofs);

    FEValues<dim>                        fe_values(*d.mapping,
                            *d.fe,
                            d.cell_quadrature,
                            update_values | update_gradients
                              | update_quadrature_points | update_JxW_values);
    FEFaceValues<dim>                    fe_face_values(*d.mapping,
                                     *d.fe,
                                     d.face_quadrature,
                                     update_values | update_quadrature_points
                                       | update_JxW_values);
    const unsigned int                   n = d.fe->n_dofs_per_cell();
    FullMatrix<double>                   cell_matrix(n, n);
    Vector<double>                       cell_rhs(n);
    std::vector<types::global_dof_index> dofs(n);

    for (const auto &cell : d.dof_handler.active_cell_iterators())
      {
        fe_values.reinit(cell);
        cell_matrix = 0;
        cell_rhs    = 0;
        for (const unsigned int q : fe_values.quadrature_point_indices())
          {
            const auto  &x    = fe_values.quadrature_point(q);
            const double beta = coefficient->value(x);
            const double f    = rhs->value(x);
            for (unsigned int i = 0; i < n; ++i)
              {
                for (unsigned int j = 0; j < n; ++j)
                  cell_matrix(i, j) += beta * fe_values.shape_grad(i, q)
                                       * fe_values.shape_grad(j, q)
                                       * fe_values.JxW(q);
                cell_rhs(i)
                  += f * fe_values.shape_value(i, q) * fe_values.JxW(q);
              }
          }
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            for (const auto &[id, flux] : neumann)
              if (face->boundary_id() == id)
                {
                  fe_face_values.reinit(cell, face);
                  for (const unsigned int q :
                       fe_face_values.quadrature_point_indices())
                    for (unsigned int i = 0; i < n; ++i)
                      cell_rhs(i)
                        += flux->value(fe_face_values.quadrature_point(q))
                           * fe_face_values.shape_value(i, q)
                           * fe_face_values.JxW(q);
                }
        cell->get_dof_indices(dofs);
        constraints.distribute_local_to_global(
          cell_matrix, cell_rhs, dofs, matrix, system_rhs);
      }

    SparseDirectUMFPACK lu;
    lu.initialize(matrix);
    lu.vmult(solution, system_rhs);
    constraints.distribute(solution);

    l2_error = h1_error = 0;
    if (!exact)
      return;
    const Quadrature<dim> error_quadrature
      = d.simplex
          ? Quadrature<dim>(QGaussSimplex<dim>(fe_parameters.degree + 2))
          : Quadrature<dim>(QGauss<dim>(fe_parameters.degree + 3));
    Vector<float> cell_errors(triangulation.n_active_cells());
    VectorTools::integrate_difference(*d.mapping,
                                      d.dof_handler,
                                      solution,
                                      *exact,
                                      cell_errors,
                                      error_quadrature,
                                      VectorTools::L2_norm);
    l2_error = VectorTools::compute_global_error(triangulation,
                                                 cell_errors,
                                                 VectorTools::L2_norm);
    VectorTools::integrate_difference(*d.mapping,
                                      d.dof_handler,
                                      solution,
                                      *exact,
                                      cell_errors,
                                      error_quadrature,
                                      VectorTools::H1_seminorm);
    h1_error = VectorTools::compute_global_error(triangulation,
                                                 cell_errors,
                                                 VectorTools::H1_seminorm);
  }


  template <int dim>
  void
  Poisson<dim>::run()
  {
    setup();
    Triangulation<dim> triangulation;
    geometry::build_triangulation(geometry_parameters, triangulation);

    // A serial verification: every process computes the same table, the
    // first one reports it.
    std::ofstream summary;
    if (!output_parameters.summary_file.empty() && parallel_tools::is_root())
      summary.open(output_parameters.summary_file);
    std::ostringstream table;
    table << "Poisson problem, " << dim << "D, degree " << fe_parameters.degree
          << "\n"
          << std::setw(8) << "cells" << std::setw(8) << "dofs" << std::setw(14)
          << "L2 error" << std::setw(8) << "rate" << std::setw(14) << "H1 error"
          << std::setw(8) << "rate"
          << "\n";
    double previous_l2 = 0, previous_h1 = 0;
    for (unsigned int cycle = 0; cycle < cycles; ++cycle)
      {
        if (cycle > 0)
          triangulation.refine_global(1);
        double       l2, h1;
        unsigned int n_dofs;
        solve_on(triangulation, l2, h1, n_dofs);
        table << std::setw(8) << triangulation.n_active_cells() << std::setw(8)
              << n_dofs << std::scientific << std::setprecision(4)
              << std::setw(14) << l2 << std::fixed << std::setprecision(2)
              << std::setw(8) << (cycle > 0 ? std::log2(previous_l2 / l2) : 0.)
              << std::scientific << std::setprecision(4) << std::setw(14) << h1
              << std::fixed << std::setprecision(2) << std::setw(8)
              << (cycle > 0 ? std::log2(previous_h1 / h1) : 0.) << "\n";
        previous_l2 = l2;
        previous_h1 = h1;
      }
    parallel_tools::screen()
      << table.str()
      << "(errors are norms of u_h - u over the domain; rate = "
         "log2 of the ratio of successive errors, mesh size halved)"
      << std::endl;
    if (summary.is_open())
      summary << table.str();
  }

  template class Poisson<1>;
  template class Poisson<2>;
  template class Poisson<3>;

  TISSUEFEM_REGISTER_PROBLEM(Poisson,
                             "Poisson",
                             "variable-coefficient Poisson equation with an "
                             "error table over refinement (verification).")

  // Files written before the name was cased as the equation's.
  namespace
  {
    const bool poisson_earlier_spelling = [] {
      ProblemRegistry::instance().add_alias("poisson", "Poisson");
      return true;
    }();
  } // namespace
} // namespace tissuefem::problems
