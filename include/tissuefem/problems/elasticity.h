#pragma once

#include <deal.II/distributed/shared_tria.h>

#include <tissuefem/adaptation/mesh_adaptation.h>
#include <tissuefem/boundary/boundary_conditions.h>
#include <tissuefem/boundary/manufactured_solution.h>
#include <tissuefem/geometry/geometry.h>
#include <tissuefem/materials/material_set.h>
#include <tissuefem/output/output_writer.h>
#include <tissuefem/problems/interface.h>
#include <tissuefem/solid/discretization.h>
#include <tissuefem/solid/solid.h>
#include <tissuefem/solvers/linear_solver.h>
#include <tissuefem/solvers/newton.h>
#include <tissuefem/time/interface.h>
#include <tissuefem/tool/grasp_tool.h>

namespace tissuefem::problems
{
  /**
   * A hyperelastic body moving under boundary conditions and loads: read
   * parameters -> build the scene (mesh, materials, boundary conditions,
   * solid) -> the chosen integrator advances the state step by step ->
   * each state goes to output -> the mesh adapts if asked. The mesh is shared
   * by all MPI processes (parallel::shared::Triangulation, partitioned by
   * METIS); each process assembles its own cells with several threads.
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
    ParameterHandler                    &prm;
    RunContext                           run_context;
    geometry::GeometryParameters         geometry_parameters;
    solid::FiniteElementParameters       fe_parameters;
    materials::MaterialParameters        material_parameters;
    boundary::BoundaryParameters         boundary_parameters;
    time::TimeParameters                 time_parameters;
    solvers::NewtonParameters            newton_parameters;
    solvers::LinearSolverParameters      linear_solver_parameters;
    output::OutputParameters             output_parameters;
    adaptation::MeshRefinementParameters refinement_parameters;
    tool::ToolParameters                 tool_parameters;
    boundary::ManufacturedParameters     manufactured_parameters;

    parallel::shared::Triangulation<dim>                 triangulation;
    std::unique_ptr<materials::MaterialSet<dim>>         materials;
    std::unique_ptr<boundary::BoundaryConditions<dim>>   boundary_conditions;
    std::unique_ptr<solid::Discretization<dim>>          discretization;
    std::unique_ptr<solid::Solid<dim>>                   solid;
    std::unique_ptr<time::Interface>                     integrator;
    std::unique_ptr<solvers::LinearSolver>               linear_solver;
    std::unique_ptr<output::OutputWriter<dim>>           writer;
    std::unique_ptr<adaptation::MeshAdaptation<dim>>     adaptation;
    std::unique_ptr<tool::GraspTool<dim>>                tool;
    std::unique_ptr<boundary::ManufacturedSolution<dim>> manufactured;

    /// Errors against the manufactured solution, accumulated over steps.
    struct ErrorHistory
    {
      double max_l2 = 0, l2_time_integral = 0, last_time = 0;
      typename boundary::ManufacturedSolution<dim>::Errors last{0, 0, 0, 0};
    } error_history;

    /// Measures the error of @p state against the manufactured solution.
    void
    record_error(const time::State &state);

    /// Writes '<Output/Directory>/run.txt' (output::RunRecord): sizes,
    /// wall times, memory, energies and errors of the finished run
    /// (@p stored_energy: int Psi dV of the final state, computed once).
    void
    write_run_record(const time::State  &state,
                     std::vector<double> step_seconds,
                     const double        assembly_seconds,
                     const double        solve_seconds,
                     const unsigned int  newton_iterations,
                     const unsigned int  rejected_attempts,
                     const double        peak_bytes,
                     const double        wall_seconds,
                     const double        stored_energy);

    /// Lets the tool grasp or release if due (before a step).
    void
    move_tool(time::State &state);

    /// Connects the linear solver (dropping factorizations before a change
    /// of mesh or constraints) and @p state's boundary values and AMG's
    /// near-null space (after one) to the solid's ChangeSignals; the
    /// connections last as long as the returned objects.
    std::vector<boost::signals2::scoped_connection>
    connect_to_changes(time::State &state);

    /// The tool force into the summary file (for regression tests).
    void
    summarize_tool(const double time, const Tensor<1, dim> &force);

    /// Hands the rigid-body modes of the current mesh to the linear
    /// solver, if it uses them.
    void
    give_near_null_space();

    /// Adapts the mesh after step @p step if due; returns whether it
    /// changed.
    bool
    adapt_mesh(const unsigned int step, time::State &state);

    /// Why this scene cannot be checkpointed, or empty.
    std::string
    checkpoint_obstacle() const;

    /// The vectors a checkpoint holds: the state and the integrator's
    /// history.
    std::vector<VectorType *>
    checkpoint_vectors(time::State &state);

    /// Writes '<Output/Directory>/checkpoint' for the state after @p step.
    void
    write_checkpoint(const unsigned int step, time::State &state);
  };
} // namespace tissuefem::problems
