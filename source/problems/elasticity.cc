#include <deal.II/base/timer.h>
#include <deal.II/dofs/dof_tools.h>

#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/problems/elasticity.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace tissuefem::problems
{
  template <int dim>
  Elasticity<dim>::Elasticity(ParameterHandler &prm, const RunContext &context)
      : prm(prm)
  {
    geometry_parameters.parse_parameters(prm);
    geometry_parameters.resolve_relative_to(context.parameter_directory);
    fe_parameters.parse_parameters(prm);
    material_parameters.parse_parameters(prm);
    boundary_parameters.parse_parameters(prm);
    time_parameters.parse_parameters(prm);
    newton_parameters.parse_parameters(prm);
    linear_solver_parameters.parse_parameters(prm);
    output_parameters.parse_parameters(prm);
  }


  template <int dim>
  void
  Elasticity<dim>::declare_parameters(ParameterHandler &)
  {
    // Every subsection this problem reads is shared with other problems and
    // declared by the application.
  }


  template <int dim>
  void
  Elasticity<dim>::setup()
  {
    geometry::build_triangulation(geometry_parameters, triangulation);
    materials
      = std::make_unique<materials::MaterialSet<dim>>(material_parameters, prm);
    materials->check_covers(triangulation);
    boundary_conditions = std::make_unique<boundary::BoundaryConditions<dim>>(
      boundary_parameters);
    boundary_conditions->check_boundary_ids(triangulation);
    discretization = std::make_unique<solid::Discretization<dim>>(triangulation,
                                                                  fe_parameters,
                                                                  dim);
    system         = std::make_unique<solid::SolidSystem<dim>>(*discretization,
                                                       *materials,
                                                       *boundary_conditions);
    {
      // Initial and boundary data must be finite where they are used.
      Vector<double> u, v;
      system->initial_state(u, v);
      require(all_finite(u),
              "Boundary conditions/Initial displacement",
              "is not finite at some node");
      require(all_finite(v),
              "Boundary conditions/Initial velocity",
              "is not finite at some node");
      system->apply_dirichlet_values(0., u);
      require(all_finite(u),
              "Boundary conditions/Dirichlet",
              "is not finite at some boundary node at t = 0");
    }
    integrator
      = time::IntegratorRegistry::instance().create(time_parameters.integrator,
                                                    prm);
    linear_solver
      = std::make_unique<solvers::LinearSolver>(linear_solver_parameters);
    if (linear_solver_parameters.type != "direct")
      {
        std::vector<std::vector<bool>> modes;
        DoFTools::extract_constant_modes(discretization->dof_handler,
                                         ComponentMask(dim, true),
                                         modes);
        linear_solver->set_constant_modes(modes);
      }
    const auto present = triangulation.get_boundary_ids();
    for (const auto id : output_parameters.reaction_boundary_ids)
      require(std::find(present.begin(), present.end(), id) != present.end(),
              "Output/Reaction boundary ids",
              "boundary id " + std::to_string(id)
                + " is on no boundary face of the mesh");
    writer
      = std::make_unique<output::OutputWriter<dim>>(output_parameters, *system);
  }


  template <int dim>
  void
  Elasticity<dim>::run()
  {
    setup();
    writer->open();

    std::cout << "tissuefem: " << dim << "D elasticity, "
              << triangulation.n_active_cells() << " cells, "
              << system->n_dofs() << " unknowns, element "
              << discretization->fe->get_name() << ", integrator '"
              << time_parameters.integrator << "'" << std::endl;
    std::ostringstream header;
    header << "cells " << triangulation.n_active_cells() << " unknowns "
           << system->n_dofs();
    writer->summary_line(header.str());

    TimerOutput timer(std::cout, TimerOutput::summary, TimerOutput::wall_times);
    Vector<double> u, v, u_new, v_new, u_tilde;
    system->initial_state(u, v);
    system->apply_dirichlet_values(0., u);
    const auto &reaction_ids = output_parameters.reaction_boundary_ids;
    u_tilde                  = u;
    writer->write_step(
      {0, 0., 0., 0, 0., 0., 0.},
      u,
      v,
      system->reaction_forces(u, u_tilde, 0., 0., reaction_ids));

    const double end_time = time_parameters.end_time;
    double       t        = 0;
    double       dt       = time_parameters.time_step;
    unsigned int step     = 0;
    while (t < end_time * (1 - 1e-12))
      {
        double                h = std::min(dt, end_time - t);
        solvers::NewtonResult result;
        for (unsigned int halvings = 0;; ++halvings)
          {
            const double mass_coefficient = integrator->mass_coefficient(h);
            integrator->predict(u, v, h, u_tilde, u_new);
            system->apply_dirichlet_values(t + h, u_new);
            auto assemble
              = [&](const Vector<double> &x, Vector<double> &r, bool jacobian) {
                  system->assemble(
                    x, u_tilde, mass_coefficient, t + h, r, jacobian);
                };
            auto solve = [&](Vector<double> &x, const Vector<double> &b) {
              linear_solver->solve(system->tangent(), x, b);
            };
            {
              TimerOutput::Scope scope(timer, "Newton (assembly + solve)");
              result = solvers::solve_newton(newton_parameters,
                                             u_new,
                                             assemble,
                                             solve);
            }
            if (result.converged)
              break;
            std::ostringstream message;
            message << "Newton failed at t = " << t + h << " with dt = " << h
                    << ": " << result.failure;
            if (halvings == time_parameters.max_step_halvings)
              throw SolverError(message.str() + "; gave up after "
                                + std::to_string(halvings)
                                + " step halvings ('Time integration/Maximum "
                                  "step halvings')");
            std::cout << "  " << message.str()
                      << "; retrying with dt = " << h / 2 << std::endl;
            h /= 2;
          }

        const auto reactions = system->reaction_forces(
          u_new, u_tilde, integrator->mass_coefficient(h), t + h, reaction_ids);
        integrator->velocity(u_new, u, v, h, v_new);
        u = u_new;
        v = v_new;
        t += h;
        ++step;
        // After a reduced step, grow back towards the requested step size.
        dt = std::min(time_parameters.time_step, 2 * h);

        const output::StepStatistics statistics{step,
                                                t,
                                                h,
                                                result.iterations,
                                                result.residual_norms.back(),
                                                result.assembly_seconds,
                                                result.solve_seconds};
        std::cout << "step " << std::setw(5) << step
                  << "  t = " << std::setw(10) << t
                  << "  dt = " << std::setw(10) << h << "  Newton "
                  << std::setw(2) << result.iterations
                  << "  |R| = " << std::scientific << std::setprecision(2)
                  << result.residual_norms.back() << std::defaultfloat
                  << std::setprecision(6) << std::endl;
        TimerOutput::Scope scope(timer, "output");
        writer->write_step(statistics, u, v, reactions);
      }

    if (output_parameters.report_rest_shape)
      {
        std::ostringstream rest;
        rest << std::setprecision(4) << "distance from rest shape "
             << system->distance_from_rest_shape(u) << " min J "
             << system->min_jacobian(u);
        writer->summary_line(rest.str());
        std::cout << rest.str()
                  << " (largest vertex distance after the best rigid fit, "
                     "length units; smallest det F)"
                  << std::endl;
      }
    std::ostringstream energy;
    energy << "final elastic energy " << std::setprecision(8)
           << system->elastic_energy(u);
    writer->summary_line(energy.str());
    std::cout << energy.str() << " (energy units, int Psi dV)" << std::endl;
  }

  template class Elasticity<1>;
  template class Elasticity<2>;
  template class Elasticity<3>;

  TISSUEFEM_REGISTER_PROBLEM(Elasticity,
                             "elasticity",
                             "a hyperelastic body under boundary conditions, "
                             "quasistatic or dynamic.")
} // namespace tissuefem::problems
