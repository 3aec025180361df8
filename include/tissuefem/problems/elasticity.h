#pragma once

#include <deal.II/base/timer.h>

#include <boost/signals2/connection.hpp>

#include <tissuefem/adaptation/mesh_adaptation.h>
#include <tissuefem/output/checkpoint.h>
#include <tissuefem/output/output_parameters.h>
#include <tissuefem/output/summary_file.h>
#include <tissuefem/postprocess/interface.h>
#include <tissuefem/problems/interface.h>
#include <tissuefem/scene/scene.h>
#include <tissuefem/solvers/linear_solver.h>
#include <tissuefem/solvers/newton.h>
#include <tissuefem/time/interface.h>

#include <memory>
#include <vector>

namespace tissuefem::problems
{
  /**
   * The run loop of a hyperelastic body under loads and constraints:
   * read parameters -> build the scene (Scene: mesh, materials,
   * loads and constraints, tool, solid) -> the chosen integrator advances
   * the state step by step, driving the solid's operators -> every
   * registered postprocessor processes each state -> the mesh adapts if
   * asked. Changes of mesh or constraints reach the linear solver, the
   * integrator, the boundary values and the postprocessors through the
   * solid's ChangeSignals; this class calls none of them by hand.
   */
  template <int dim>
  class Elasticity : public Interface
  {
  public:
    Elasticity(ParameterHandler &prm, const RunContext &context);

    /// Declares the subsections only this problem reads (the scene's and
    /// the postprocessors'); the shared ones are declared by the
    /// application.
    static void
    declare_parameters(ParameterHandler &prm);

    void
    setup() override;

    void
    run() override;

  private:
    ParameterHandler                    &prm;
    RunContext                           run_context;
    time::TimeParameters                 time_parameters;
    solvers::NewtonParameters            newton_parameters;
    output::OutputParameters             output_parameters;
    adaptation::MeshRefinementParameters refinement_parameters;

    std::unique_ptr<Scene<dim>>                      scene;
    std::unique_ptr<time::Interface>                 integrator;
    std::unique_ptr<solvers::LinearSolver>           linear_solver;
    std::unique_ptr<adaptation::MeshAdaptation<dim>> adaptation;
    std::unique_ptr<output::SummaryFile>             summary;
    std::unique_ptr<postprocess::Context<dim>>       postprocess_context;
    /// The registered postprocessors by name, in the order they run.
    std::vector<
      std::pair<std::string, std::unique_ptr<postprocess::Interface<dim>>>>
      postprocessors;

    /// Creates and initializes every registered postprocessor.
    void
    create_postprocessors();

    /// Lets each tool grasp or release if due (before a step).
    void
    move_tool(time::State &state);

    /// Connects the linear solver (dropping factorizations before a change
    /// of mesh or constraints) and @p state's boundary values and AMG's
    /// near-null space (after one) to the solid's ChangeSignals; the
    /// connections last as long as the returned objects.
    std::vector<boost::signals2::scoped_connection>
    connect_to_changes(time::State &state);

    /// Hands the rigid-body modes of the current mesh to the linear
    /// solver, if it uses them.
    void
    give_near_null_space();

    /// Creates the output files, or continues those of a checkpoint
    /// ('--restart'); returns the step to continue from (0: a new run).
    unsigned int
    start_outputs(time::State &state);

    /// Runs every postprocessor on the state after step @p step.
    void
    postprocess(const unsigned int      step,
                const time::StepReport &report,
                const time::State      &state);

    /// Lets the tools act and the integrator take one step (@p report);
    /// false if a live session ended before it.
    bool
    take_step(time::State &state, time::StepReport &report);

    /// The end-of-run reports: postprocessors' finish(), run.txt, and the
    /// run's cost on screen.
    void
    finish(const time::State &state, postprocess::RunTotals &totals);

    /// Adapts the mesh after step @p step if due.
    void
    adapt_mesh(const unsigned int step, time::State &state);

    /// The steps from @p state (after step @p step) to the end time, each
    /// followed by its outputs; counts into @p totals, times into @p timer.
    void
    run_steps(time::State            &state,
              unsigned int           &step,
              TimerOutput            &timer,
              postprocess::RunTotals &totals);

    /// Lets every postprocessor wait after a state (Interface::wait()),
    /// timed in @p timer apart from the output.
    void
    wait_for_postprocessors(TimerOutput &timer, const time::State &state);

    /// Why this scene cannot be checkpointed, or empty.
    std::string
    checkpoint_obstacle() const;

    /// The state and the integrator's history: what a checkpoint holds
    /// and a mesh adaptation transfers.
    std::vector<VectorType *>
    state_vectors(time::State &state);

    /// The files the run appends to step by step (summary file and
    /// postprocessors'), whose sizes a checkpoint records.
    std::vector<std::string>
    appended_files() const;

    /// Writes '<Output/Directory>/checkpoint' for the state after @p step.
    void
    write_checkpoint(const unsigned int step, time::State &state);

    /// On SIGINT/SIGTERM after step @p step: checkpoints if it can and
    /// throws Interrupted.
    void
    stop_if_interrupted(const unsigned int step, time::State &state);
  };
} // namespace tissuefem::problems
