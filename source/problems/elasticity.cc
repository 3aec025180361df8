#include <deal.II/base/multithread_info.h>
#include <deal.II/base/timer.h>

#include <tissuefem/adaptation/stress_jump.h>
#include <tissuefem/base/interruption.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/output/run_record.h>
#include <tissuefem/problems/elasticity.h>
#include <tissuefem/solid/quantities.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <numeric>
#include <sstream>

namespace tissuefem::problems
{
  template <int dim>
  Elasticity<dim>::Elasticity(ParameterHandler &prm, const RunContext &context)
      : prm(prm)
      , run_context(context)
      , triangulation(parallel_tools::communicator(),
                      Triangulation<dim>::limit_level_difference_at_vertices,
                      /*allow_artificial_cells=*/false,
                      parallel::shared::Triangulation<dim>::partition_metis)
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
    refinement_parameters.parse_parameters(prm);
    tool_parameters.parse_parameters(prm);
    manufactured_parameters.parse_parameters(prm);
  }


  template <int dim>
  void
  Elasticity<dim>::declare_parameters(ParameterHandler &prm)
  {
    // The other subsections this problem reads are shared with other
    // problems and declared by the application.
    tool::ToolParameters::declare_parameters(prm);
    boundary::ManufacturedParameters::declare_parameters(prm);
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
    if (manufactured_parameters.enabled)
      {
        require(!tool_parameters.enabled,
                "Manufactured solution/Enabled",
                "cannot be combined with a tool");
        manufactured = std::make_unique<boundary::ManufacturedSolution<dim>>(
          manufactured_parameters,
          *materials,
          triangulation,
          time_parameters.integrator != "quasistatic");
        manufactured->impose_on(*boundary_conditions);
      }
    discretization = std::make_unique<solid::Discretization<dim>>(triangulation,
                                                                  fe_parameters,
                                                                  dim);
    solid          = std::make_unique<solid::Solid<dim>>(*discretization,
                                                *materials,
                                                *boundary_conditions);
    {
      // Initial and boundary data must be finite where they are used.
      VectorType u, v;
      solid->initial_state(u, v);
      require(all_finite(u),
              "Boundary conditions/Initial displacement",
              "is not finite at some node");
      require(all_finite(v),
              "Boundary conditions/Initial velocity",
              "is not finite at some node");
      solid->apply_dirichlet_values(0., u);
      require(all_finite(u),
              "Boundary conditions/Dirichlet",
              "is not finite at some boundary node at t = 0");
    }
    integrator
      = time::IntegratorRegistry::instance().create(time_parameters.integrator,
                                                    prm);
    linear_solver
      = std::make_unique<solvers::LinearSolver>(linear_solver_parameters);
    give_near_null_space();
    const auto present = triangulation.get_boundary_ids();
    for (const auto id : output_parameters.reaction_boundary_ids)
      require(std::find(present.begin(), present.end(), id) != present.end(),
              "Output/Reaction boundary ids",
              "boundary id " + std::to_string(id)
                + " is on no boundary face of the mesh");
    writer
      = std::make_unique<output::OutputWriter<dim>>(output_parameters, *solid);
    adaptation
      = std::make_unique<adaptation::MeshAdaptation<dim>>(refinement_parameters,
                                                          triangulation,
                                                          *solid);
    if (tool_parameters.enabled)
      {
        require(refinement_parameters.indicator == "none",
                "Mesh refinement/Indicator",
                "must be 'none' with a tool (held vertices are those of the "
                "initial mesh)");
        tool = std::make_unique<tool::GraspTool<dim>>(tool_parameters,
                                                      triangulation);
      }
  }


  template <int dim>
  void
  Elasticity<dim>::summarize_tool(const double time, const Tensor<1, dim> &f)
  {
    std::ostringstream line;
    line << std::setprecision(8) << "t = " << time << " tool force =";
    for (unsigned int d = 0; d < dim; ++d)
      line << ' ' << f[d];
    writer->summary_line(line.str());
  }


  template <int dim>
  void
  Elasticity<dim>::move_tool(time::State &state)
  {
    // The constraints change; the solid announces it (connect_to_changes).
    if (tool && tool->due(state.time))
      tool->act(state, *solid);
  }


  template <int dim>
  std::vector<boost::signals2::scoped_connection>
  Elasticity<dim>::connect_to_changes(time::State &state)
  {
    std::vector<boost::signals2::scoped_connection> connections;
    // Factorizations and AMG hierarchies refer to the old matrix.
    connections.emplace_back(solid->signals.about_to_change.connect(
      [this]() { linear_solver->reset(); }));
    // Nodes new on the Dirichlet boundary, or newly held, get their
    // prescribed values; AMG's near-null space belongs to the mesh.
    connections.emplace_back(solid->signals.changed.connect([this, &state]() {
      solid->apply_dirichlet_values(state.time, state.u);
      give_near_null_space();
    }));
    return connections;
  }


  template <int dim>
  std::string
  Elasticity<dim>::checkpoint_obstacle() const
  {
    if (!integrator->checkpointable())
      return "integrator '" + time_parameters.integrator
             + "' cannot be checkpointed (with these settings)";
    if (tool)
      return "a scene with a tool cannot be checkpointed";
    if (refinement_parameters.indicator != "none")
      return "a scene with mesh refinement cannot be checkpointed";
    return {};
  }


  template <int dim>
  std::vector<VectorType *>
  Elasticity<dim>::checkpoint_vectors(time::State &state)
  {
    std::vector<VectorType *> vectors = {&state.u, &state.v, &state.a};
    for (VectorType *v : integrator->history())
      vectors.push_back(v);
    return vectors;
  }


  template <int dim>
  void
  Elasticity<dim>::write_checkpoint(const unsigned int step, time::State &state)
  {
    output::Checkpoint checkpoint;
    checkpoint.step               = step;
    checkpoint.time               = state.time;
    checkpoint.n_processes        = parallel_tools::n_processes();
    checkpoint.n_dofs             = solid->n_dofs();
    checkpoint.integrator         = time_parameters.integrator;
    checkpoint.integrator_scalars = integrator->checkpoint_scalars();
    writer->fill_checkpoint(checkpoint);
    const auto vectors = checkpoint_vectors(state);
    output::write_checkpoint(output_parameters.directory + "/checkpoint",
                             checkpoint,
                             {vectors.begin(), vectors.end()});
  }


  template <int dim>
  void
  Elasticity<dim>::give_near_null_space()
  {
    // Only AMG uses them; they belong to the current mesh.
    if (linear_solver_parameters.type == "cg amg")
      linear_solver->set_near_null_space(discretization->rigid_body_modes(),
                                         dim);
  }


  template <int dim>
  bool
  Elasticity<dim>::adapt_mesh(const unsigned int step, time::State &state)
  {
    if (!adaptation->due(step))
      return false;
    std::vector<VectorType *> vectors = {&state.u, &state.v, &state.a};
    for (VectorType *v : integrator->history())
      vectors.push_back(v);
    // The solid announces the change to the solver, the integrator and
    // the state's boundary values (connect_to_changes, run()).
    if (!adaptation->adapt(state.u, state.time, vectors))
      return false;
    parallel_tools::screen()
      << "  mesh adapted: " << triangulation.n_active_cells() << " cells, "
      << solid->n_dofs() << " unknowns" << std::endl;
    return true;
  }


  namespace
  {
    /// The share of steps within the budget, median and worst step time.
    std::string
    real_time_report(std::vector<double> seconds,
                     const double        budget,
                     const double        simulated)
    {
      if (seconds.empty())
        return "real time: no steps";
      const double wall = std::accumulate(seconds.begin(), seconds.end(), 0.);
      std::sort(seconds.begin(), seconds.end());
      const auto within
        = std::upper_bound(seconds.begin(), seconds.end(), budget)
          - seconds.begin();
      std::ostringstream s;
      s << "real time: " << std::setprecision(3)
        << 100. * within / seconds.size() << " % of " << seconds.size()
        << " steps within the budget of " << budget
        << " s (wall clock); median step " << seconds[seconds.size() / 2]
        << " s, worst " << seconds.back() << " s; simulated time per "
        << "wall-clock time of the steps " << simulated / wall
        << " (1 or more keeps up with real time)";
      return s.str();
    }
  } // namespace


  template <int dim>
  void
  Elasticity<dim>::record_error(const time::State &state)
  {
    if (!manufactured)
      return;
    VectorType u;
    discretization->initialize_vector(u, true);
    u            = state.u;
    const auto e = manufactured->errors(*discretization, u, state.time);
    auto      &h = error_history;
    h.max_l2     = std::max(h.max_l2, e.l2);
    // Rectangle rule on the step just taken: sum over steps of dt e^2.
    h.l2_time_integral += (state.time - h.last_time) * e.l2 * e.l2;
    h.last_time = state.time;
    h.last      = e;
  }


  template <int dim>
  void
  Elasticity<dim>::write_run_record(const time::State  &state,
                                    std::vector<double> step_seconds,
                                    const double        assembly_seconds,
                                    const double        solve_seconds,
                                    const unsigned int  newton_iterations,
                                    const unsigned int  rejected_attempts,
                                    const double        peak_bytes,
                                    const double        wall_seconds,
                                    const double        stored)
  {
    const double steps_wall
      = std::accumulate(step_seconds.begin(), step_seconds.end(), 0.);
    std::sort(step_seconds.begin(), step_seconds.end());
    const auto percentile = [&](const double p) {
      return step_seconds.empty()
               ? 0.
               : step_seconds[std::min<std::size_t>(
                 step_seconds.size() - 1,
                 static_cast<std::size_t>(p * step_seconds.size()))];
    };
    // The estimator's effectivity where the true error is known
    // (hypercube meshes: the estimator evaluates neighbours by their
    // reference coordinates).
    double estimate = -1;
    if (manufactured && !discretization->simplex)
      {
        VectorType u;
        discretization->initialize_vector(u, true);
        u        = state.u;
        estimate = adaptation::stress_jump_estimate(*solid, u, state.time);
      }
    const double kinetic = solid->kinetic_energy(state.v);
    if (!parallel_tools::is_root())
      return;
    output::RunRecord r;
    r.add("processes", parallel_tools::n_processes(), "MPI processes");
    r.add("threads", MultithreadInfo::n_threads(), "threads per process");
    r.add("cells", triangulation.n_active_cells(), "active cells at the end");
    r.add("unknowns", solid->n_dofs(), "displacement unknowns at the end");
    r.add("steps",
          step_seconds.size(),
          "steps reported (rows of statistics.csv)");
    r.add("simulated time", state.time, "time units reached");
    r.add("newton iterations", newton_iterations, "sum over steps");
    r.add("rejected attempts", rejected_attempts, "sum over steps");
    r.add("wall total", wall_seconds, "s, set-up, steps and output");
    r.add("wall steps", steps_wall, "s, sum of the integrator's steps");
    r.add("wall assembly",
          assembly_seconds,
          "s, residual and Jacobian assembly in the steps");
    r.add("wall solve", solve_seconds, "s, linear solves in the steps");
    r.add("step median", percentile(0.5), "s wall per step, median");
    r.add("step p95", percentile(0.95), "s wall per step, 95th percentile");
    r.add("step max", percentile(1.), "s wall per step, largest");
    r.add("peak memory", peak_bytes / 1e6, "MB resident, sum over processes");
    r.add("stored energy", stored, "energy units, int Psi dV at the end");
    r.add("kinetic energy", kinetic, "energy units, 1/2 v.M v at the end");
    if (manufactured)
      {
        const auto &e = error_history.last;
        r.add("L2 error", e.l2, "length units, ||u_h - u||_L2 at the end");
        r.add("H1 error",
              e.h1,
              "||Grad(u_h - u)||_L2 at the end (length^(dim/2))");
        r.add("relative L2 error",
              e.l2 / e.l2_exact,
              "||u_h - u||/||u|| at the end");
        r.add("relative H1 error",
              e.h1 / e.h1_exact,
              "||Grad(u_h - u)||/||Grad u|| at the end");
        r.add("max L2 error",
              error_history.max_l2,
              "length units, largest over the steps");
        r.add("L2L2 error",
              std::sqrt(error_history.l2_time_integral),
              "(sum over steps of dt ||u_h - u||_L2^2)^(1/2)");
        if (estimate >= 0)
          {
            r.add("error estimate",
                  estimate,
                  "stress-jump estimate of the H1 seminorm error at the end");
            r.add("effectivity",
                  estimate / e.h1,
                  "error estimate / H1 error (1: exact estimate)");
          }
      }
    r.write(output_parameters.directory + "/run.txt");
  }


  template <int dim>
  void
  Elasticity<dim>::run()
  {
    const auto run_start = std::chrono::steady_clock::now();
    setup();
    // Only this problem finishes a step and checkpoints on SIGINT/SIGTERM;
    // the others keep the default (immediate) end.
    install_interruption_handlers();
    auto &screen = parallel_tools::screen();
    // The integrator may still reject its input (an explicit step above
    // the critical one): before any file exists.
    time::Context context{*solid,
                          time_parameters,
                          newton_parameters,
                          *linear_solver};
    time::State   state;
    solid->initial_state(state.u, state.v);
    solid->apply_dirichlet_values(0., state.u);
    const auto follow_changes = connect_to_changes(state);
    move_tool(state);
    integrator->initialize(context, state);
    // Once started, the integrator rebuilds its work vectors and masses
    // after each change, last, when the state is on the new mesh and
    // constraints.
    const boost::signals2::scoped_connection restart_integrator
      = solid->signals.changed.connect(
        [this]() { integrator->mesh_changed(); });
    const std::string why_no_checkpoint = checkpoint_obstacle();
    const bool        restart = !run_context.restart_directory.empty();
    if ((restart || output_parameters.checkpoint_interval > 0)
        && !why_no_checkpoint.empty())
      throw InputError(std::string(restart ? "--restart"
                                           : "Parameter 'Output/Checkpoint "
                                             "interval'")
                       + ": " + why_no_checkpoint);
    unsigned int step = 0;
    if (restart)
      {
        const auto checkpoint
          = output::read_checkpoint(run_context.restart_directory,
                                    checkpoint_vectors(state));
        require(checkpoint.integrator == time_parameters.integrator
                  && checkpoint.n_dofs == solid->n_dofs(),
                "--restart",
                "the checkpoint was written by a run with integrator '"
                  + checkpoint.integrator + "' and "
                  + std::to_string(checkpoint.n_dofs)
                  + " unknowns; this scene has '" + time_parameters.integrator
                  + "' and " + std::to_string(solid->n_dofs()));
        state.time = checkpoint.time;
        step       = checkpoint.step;
        integrator->restore_scalars(checkpoint.integrator_scalars);
        writer->resume(checkpoint);
        screen << "tissuefem: continuing from the checkpoint at step " << step
               << ", t = " << state.time << std::endl;
      }
    else
      writer->open();
    if (tool)
      tool->open(output_parameters.directory);

    screen << "tissuefem: " << dim << "D elasticity, "
           << triangulation.n_active_cells() << " cells, " << solid->n_dofs()
           << " unknowns, element " << discretization->fe->get_name()
           << ", integrator '" << time_parameters.integrator
           << "', linear solver '" << linear_solver_parameters.type << "'"
           << "\n"
           << geometry::describe_boundary_ids(triangulation) << std::endl;
    TimerOutput timer(screen, TimerOutput::summary, TimerOutput::wall_times);
    const auto &reaction_ids = output_parameters.reaction_boundary_ids;
    if (!restart)
      {
        std::ostringstream header;
        header << "cells " << triangulation.n_active_cells() << " unknowns "
               << solid->n_dofs();
        writer->summary_line(header.str());
        writer->write_step(
          0,
          time::StepReport(),
          state,
          solid->reaction_forces(state.u, state.a, state.time, reaction_ids));
        if (tool)
          summarize_tool(state.time, tool->record(state, *solid));
      }
    record_error(state);

    const double        end_time = time_parameters.end_time;
    std::vector<double> step_seconds;
    bool                mesh_changed = false;
    struct
    {
      double       assembly = 0, solve = 0;
      unsigned int newton = 0, rejected = 0;
    } totals;
    while (state.time < end_time * (1 - 1e-12))
      {
        time::StepReport report;
        {
          // A live tool: positions must cover the step before it starts.
          if (tool
              && !tool->synchronize(
                std::min(state.time + time_parameters.time_step, end_time)))
            {
              screen << "live session ended at t = " << state.time << ": "
                     << tool->live_end() << std::endl;
              break;
            }
          TimerOutput::Scope scope(timer, "time steps (integrator)");
          move_tool(state);
          const auto start    = std::chrono::steady_clock::now();
          report              = integrator->advance(state, end_time);
          report.step_seconds = std::chrono::duration<double>(
                                  std::chrono::steady_clock::now() - start)
                                  .count();
        }
        step_seconds.push_back(report.step_seconds);
        totals.assembly += report.assembly_seconds;
        totals.solve += report.solve_seconds;
        totals.newton += report.newton_iterations;
        totals.rejected += report.rejected_attempts;
        report.stored_energy  = solid->stored_energy(state.u);
        report.kinetic_energy = solid->kinetic_energy(state.v);
        ++step;
        TimerOutput::Scope scope(timer, "output");
        const auto         reactions
          = solid->reaction_forces(state.u, state.a, state.time, reaction_ids);
        screen << "step " << std::setw(5) << step << "  t = " << std::setw(10)
               << state.time << "  dt = " << std::setw(10) << report.dt
               << "  Newton " << std::setw(2) << report.newton_iterations
               << "  |R| = " << std::scientific << std::setprecision(2)
               << report.residual_norm << std::defaultfloat
               << std::setprecision(6) << std::endl;
        writer->write_step(step, report, state, reactions, mesh_changed);
        record_error(state);
        if (tool)
          summarize_tool(state.time, tool->record(state, *solid));
        const unsigned int interval = output_parameters.checkpoint_interval;
        if (interval > 0 && step % interval == 0)
          write_checkpoint(step, state);
        if (const int signal = interruption_requested())
          {
            std::ostringstream time_text;
            time_text << std::setprecision(10) << state.time;
            std::string what = "signal " + std::to_string(signal)
                               + " after step " + std::to_string(step)
                               + ", t = " + time_text.str()
                               + " (time units); outputs written up to there";
            if (why_no_checkpoint.empty())
              {
                write_checkpoint(step, state);
                what += "; continue with --restart "
                        + output_parameters.directory + "/checkpoint";
              }
            else
              what += "; no checkpoint (" + why_no_checkpoint + ")";
            throw Interrupted(signal, what);
          }
        // The state just written is an equilibrium (or solution) on its
        // mesh; the next step starts on the adapted one.
        if (state.time < end_time * (1 - 1e-12))
          mesh_changed = adapt_mesh(step, state);
      }

    VectorType u;
    discretization->initialize_vector(u, true);
    u = state.u;
    if (output_parameters.report_rest_shape)
      {
        std::ostringstream rest;
        rest << std::setprecision(4) << "distance from rest shape "
             << solid::distance_from_rest_shape(*discretization, u) << " min J "
             << solid::min_jacobian(*discretization, u);
        writer->summary_line(rest.str());
        screen << rest.str()
               << " (largest vertex distance after the best rigid fit, "
                  "length units; smallest det F)"
               << std::endl;
      }
    const double       final_energy = solid->stored_energy(state.u);
    std::ostringstream energy;
    energy << "final elastic energy " << std::setprecision(8) << final_energy;
    writer->summary_line(energy.str());
    screen << energy.str() << " (energy units, int Psi dV)" << std::endl;
    Utilities::System::MemoryStats memory;
    Utilities::System::get_memory_stats(memory);
    const double peak_bytes
      = Utilities::MPI::sum(1024. * memory.VmHWM,
                            parallel_tools::communicator());
    screen << "peak memory (resident, all processes): " << peak_bytes / 1e6
           << " MB, " << peak_bytes / solid->n_dofs() << " bytes per unknown"
           << std::endl;
    if (const std::string s = integrator->summary(); !s.empty())
      screen << s << std::endl;
    screen << real_time_report(step_seconds,
                               time_parameters.real_time_budget,
                               state.time)
           << std::endl;
    if (tool)
      screen << tool->summary() << std::endl;
    if (manufactured)
      {
        const auto &e = error_history.last;
        screen << "error against the manufactured solution at t = "
               << state.time << ": L2 " << e.l2 << " (length units; relative "
               << e.l2 / e.l2_exact << "), H1 seminorm " << e.h1
               << " (relative " << e.h1 / e.h1_exact << "); largest L2 error "
               << "over the steps " << error_history.max_l2 << std::endl;
      }
    write_run_record(state,
                     step_seconds,
                     totals.assembly,
                     totals.solve,
                     totals.newton,
                     totals.rejected,
                     peak_bytes,
                     std::chrono::duration<double>(
                       std::chrono::steady_clock::now() - run_start)
                       .count(),
                     final_energy);
    const auto &linear = linear_solver->statistics();
    screen << "linear solver: " << linear.solves << " solves, "
           << linear.iterations << " Krylov iterations, " << linear.setups
           << " symbolic factorizations or AMG builds (" << linear.setup_seconds
           << " s), " << linear.factorizations << " numeric factorizations"
           << std::endl;
  }

  template class Elasticity<1>;
  template class Elasticity<2>;
  template class Elasticity<3>;

  TISSUEFEM_REGISTER_PROBLEM(Elasticity,
                             "elasticity",
                             "a hyperelastic body under boundary conditions, "
                             "quasistatic or dynamic.")
} // namespace tissuefem::problems
