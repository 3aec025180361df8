#pragma once

#include <deal.II/grid/tria.h>

#include <tissuefem/boundary/boundary_conditions.h>
#include <tissuefem/geometry/geometry.h>
#include <tissuefem/materials/material_set.h>
#include <tissuefem/output/output_writer.h>
#include <tissuefem/problems/interface.h>
#include <tissuefem/solid/discretization.h>
#include <tissuefem/solid/solid_system.h>
#include <tissuefem/solvers/linear_solver.h>
#include <tissuefem/solvers/newton.h>
#include <tissuefem/time/interface.h>

namespace tissuefem::problems
{
  /**
   * A hyperelastic body moving under boundary conditions and loads:
   * read parameters -> build mesh, materials, boundary conditions -> for
   * each step: predict, Newton (assemble, solve) -> output. A step whose
   * Newton iteration fails is retried with half the step size.
   */
  template <int dim>
  class Elasticity : public Interface
  {
  public:
    Elasticity(ParameterHandler &prm, const RunContext &context);

    /// Declares the subsections this problem reads (besides the global ones).
    static void
    declare_parameters(ParameterHandler &prm);

    void
    setup() override;

    void
    run() override;

  private:
    ParameterHandler               &prm;
    geometry::GeometryParameters    geometry_parameters;
    solid::FiniteElementParameters  fe_parameters;
    materials::MaterialParameters   material_parameters;
    boundary::BoundaryParameters    boundary_parameters;
    time::TimeParameters            time_parameters;
    solvers::NewtonParameters       newton_parameters;
    solvers::LinearSolverParameters linear_solver_parameters;
    output::OutputParameters        output_parameters;

    Triangulation<dim>                                 triangulation;
    std::unique_ptr<materials::MaterialSet<dim>>       materials;
    std::unique_ptr<boundary::BoundaryConditions<dim>> boundary_conditions;
    std::unique_ptr<solid::Discretization<dim>>        discretization;
    std::unique_ptr<solid::SolidSystem<dim>>           system;
    std::unique_ptr<time::Interface>                   integrator;
    std::unique_ptr<solvers::LinearSolver>             linear_solver;
    std::unique_ptr<output::OutputWriter<dim>>         writer;
  };
} // namespace tissuefem::problems
