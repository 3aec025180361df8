#include <deal.II/base/timer.h>

#include <tissuefem/base/interruption.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/output/run_record.h>
#include <tissuefem/problems/elasticity.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <numeric>
#include <sstream>

namespace tissuefem::problems
{
  template <int dim>
  Elasticity<dim>::Elasticity(ParameterHandler &prm, const RunContext &context)
      : prm(prm)
      , run_context(context)
  {
    time_parameters.parse_parameters(prm);
    newton_parameters.parse_parameters(prm);
    output_parameters.parse_parameters(prm);
    refinement_parameters.parse_parameters(prm);
  }


  template <int dim>
  void
  Elasticity<dim>::declare_parameters(ParameterHandler &prm)
  {
    Scene<dim>::declare_parameters(prm);
    postprocess::PostprocessorRegistry<dim>::instance().declare_parameters(prm);
  }


  template <int dim>
  void
  Elasticity<dim>::setup()
  {
    scene = std::make_unique<Scene<dim>>(prm, run_context.parameter_directory);
    for (const auto &[name, tool] : scene->tools)
      require(tool->allows_refinement()
                || refinement_parameters.indicator == "none",
              "Mesh refinement/Indicator",
              "must be 'none' with the " + name
                + " tool (held vertices are those of the initial mesh)");
    integrator
      = time::IntegratorRegistry::instance().create(time_parameters.integrator,
                                                    prm);
    linear_solver = std::make_unique<solvers::LinearSolver>(prm);
    give_near_null_space();
    adaptation
      = std::make_unique<adaptation::MeshAdaptation<dim>>(refinement_parameters,
                                                          scene->triangulation,
                                                          *scene->solid);
    create_postprocessors();
  }


  template <int dim>
  void
  Elasticity<dim>::create_postprocessors()
  {
    summary = std::make_unique<output::SummaryFile>(
      output_parameters.summary_file,
      output_parameters.summary_interval,
      output_parameters.summary_displacement_unit);
    postprocess_context = std::make_unique<postprocess::Context<dim>>(
      postprocess::Context<dim>{*scene,
                                output_parameters.directory,
                                *summary,
                                run_context.parameter_file});
    // The registry's (alphabetical) order is the order of their lines in
    // the summary file.
    postprocessors.clear();
    for (const auto &[name, entry] :
         postprocess::PostprocessorRegistry<dim>::instance().all())
      {
        postprocessors.emplace_back(name, entry.create(prm));
        postprocessors.back().second->initialize(*postprocess_context);
      }
  }


  template <int dim>
  void
  Elasticity<dim>::move_tool(time::State &state)
  {
    // The constraints change; the solid announces it (connect_to_changes).
    for (auto &[name, tool] : scene->tools)
      if (tool->due(state.time))
        tool->act(state, *scene->solid);
  }


  template <int dim>
  std::vector<boost::signals2::scoped_connection>
  Elasticity<dim>::connect_to_changes(time::State &state)
  {
    std::vector<boost::signals2::scoped_connection> connections;
    auto &signals = scene->solid->signals;
    // Factorizations and AMG hierarchies refer to the old matrix.
    connections.emplace_back(
      signals.about_to_change.connect([this]() { linear_solver->reset(); }));
    // Nodes new on the Dirichlet boundary, or newly held, get their
    // prescribed values; AMG's near-null space belongs to the mesh.
    connections.emplace_back(signals.changed.connect([this, &state]() {
      scene->solid->apply_dirichlet_values(state.time, state.u);
      give_near_null_space();
    }));
    return connections;
  }


  template <int dim>
  void
  Elasticity<dim>::give_near_null_space()
  {
    // Only AMG uses them; they belong to the current mesh.
    if (linear_solver->uses_near_null_space())
      linear_solver->set_near_null_space(
        scene->discretization->rigid_body_modes(), dim);
  }


  template <int dim>
  std::string
  Elasticity<dim>::checkpoint_obstacle() const
  {
    if (!integrator->checkpointable())
      return "integrator '" + time_parameters.integrator
             + "' cannot be checkpointed (with these settings)";
    for (const auto &[name, tool] : scene->tools)
      if (!tool->checkpointable())
        return "the " + name + " tool cannot be checkpointed now";
    if (adaptation->enabled())
      return "a scene with mesh refinement cannot be checkpointed";
    if (scene->obstacle_contact && scene->obstacle_contact->keeps_history())
      return "contact by the augmented Lagrangian or with friction keeps "
             "multipliers and stick points that a checkpoint does not hold";
    return {};
  }


  template <int dim>
  std::vector<VectorType *>
  Elasticity<dim>::state_vectors(time::State &state)
  {
    std::vector<VectorType *> vectors = {&state.u, &state.v, &state.a};
    for (VectorType *v : integrator->history())
      vectors.push_back(v);
    return vectors;
  }


  template <int dim>
  std::vector<std::string>
  Elasticity<dim>::appended_files() const
  {
    std::vector<std::string> files;
    if (!summary->path().empty())
      files.push_back(summary->path());
    for (const auto &[name, postprocessor] : postprocessors)
      for (const std::string &f : postprocessor->files())
        files.push_back(f);
    return files;
  }


  template <int dim>
  void
  Elasticity<dim>::write_checkpoint(const unsigned int step, time::State &state)
  {
    output::Checkpoint checkpoint;
    checkpoint.step        = step;
    checkpoint.time        = state.time;
    checkpoint.n_processes = parallel_tools::n_processes();
    checkpoint.n_dofs      = scene->solid->n_dofs();
    checkpoint.distributed_mesh
      = !geometry::holds_whole_mesh<dim>(scene->triangulation);
    checkpoint.integrator         = time_parameters.integrator;
    checkpoint.integrator_scalars = integrator->checkpoint_scalars();
    for (const auto &[name, postprocessor] : postprocessors)
      checkpoint.postprocessor_state[name] = postprocessor->save();
    // (Root's sizes reach the other processes through its file.)
    if (parallel_tools::is_root())
      for (const std::string &file : appended_files())
        {
          std::error_code code;
          const auto      size        = std::filesystem::file_size(file, code);
          checkpoint.file_sizes[file] = code ? 0 : size;
        }
    const auto vectors = state_vectors(state);
    output::write_checkpoint(output_parameters.directory + "/checkpoint",
                             checkpoint,
                             {vectors.begin(), vectors.end()});
  }


  template <int dim>
  void
  Elasticity<dim>::stop_if_interrupted(const unsigned int step,
                                       time::State       &state)
  {
    const int signal = interruption_requested();
    if (!signal)
      return;
    std::ostringstream time_text;
    time_text << std::setprecision(10) << state.time;
    std::string what = "signal " + std::to_string(signal) + " after step "
                       + std::to_string(step) + ", t = " + time_text.str()
                       + " (time units); outputs written up to there";
    if (const std::string why = checkpoint_obstacle(); why.empty())
      {
        write_checkpoint(step, state);
        what += "; continue with --restart " + output_parameters.directory
                + "/checkpoint";
      }
    else
      what += "; no checkpoint (" + why + ")";
    throw Interrupted(signal, what);
  }


  namespace
  {
    /// Cuts each file of @p checkpoint back to its size then (process 0;
    /// the outcome is shared, so every process fails alike).
    void
    cut_back_files(const output::Checkpoint       &checkpoint,
                   const std::vector<std::string> &files)
    {
      std::string error;
      if (parallel_tools::is_root())
        for (const std::string &file : files)
          {
            const auto      found = checkpoint.file_sizes.find(file);
            std::error_code code;
            if (found == checkpoint.file_sizes.end())
              error = "'" + file
                      + "' is not among the checkpoint's files "
                        "(another Output section?)";
            else if (std::filesystem::file_size(file, code) < found->second
                     || code)
              error = "'" + file + "' is shorter than at the checkpoint";
            else
              {
                std::filesystem::resize_file(file, found->second, code);
                if (code)
                  error = "cannot cut '" + file + "' back: " + code.message();
              }
          }
      error = Utilities::MPI::broadcast(parallel_tools::communicator(), error);
      if (!error.empty())
        throw InputError("--restart: " + error);
    }

    /// Creates the output directory (process 0), after the summary file,
    /// so that a summary file that cannot be written leaves nothing.
    void
    create_directory(const std::string &directory)
    {
      std::error_code code;
      std::filesystem::create_directories(directory, code);
      require(!code,
              "Output/Directory",
              "cannot create '" + directory + "': " + code.message());
    }
  } // namespace


  template <int dim>
  unsigned int
  Elasticity<dim>::start_outputs(time::State &state)
  {
    const std::string why_no_checkpoint = checkpoint_obstacle();
    const bool        restart = !run_context.restart_directory.empty();
    if ((restart || output_parameters.checkpoint_interval > 0)
        && !why_no_checkpoint.empty())
      throw InputError(std::string(restart ? "--restart"
                                           : "Parameter 'Output/Checkpoint "
                                             "interval'")
                       + ": " + why_no_checkpoint);
    if (!restart)
      {
        // Process 0 checks and creates; the others learn the outcome.
        std::string error;
        if (parallel_tools::is_root())
          try
            {
              summary->open();
              create_directory(output_parameters.directory);
            }
          catch (const InputError &e)
            {
              error = e.what();
            }
        if (const std::string e = parallel_tools::first_error(error);
            !e.empty())
          throw InputError(e);
        // Every postprocessor opens on every process (some open links
        // together), even after another failed; then all fail alike.
        for (auto &[name, postprocessor] : postprocessors)
          try
            {
              postprocessor->open();
            }
          catch (const InputError &e)
            {
              if (error.empty())
                error = e.what();
            }
        if (const std::string e = parallel_tools::first_error(error);
            !e.empty())
          throw InputError(e);
        return 0;
      }
    const auto checkpoint
      = output::read_checkpoint(run_context.restart_directory,
                                state_vectors(state));
    require(checkpoint.integrator == time_parameters.integrator
              && checkpoint.n_dofs == scene->solid->n_dofs(),
            "--restart",
            "the checkpoint was written by a run with integrator '"
              + checkpoint.integrator + "' and "
              + std::to_string(checkpoint.n_dofs)
              + " unknowns; this scene has '" + time_parameters.integrator
              + "' and " + std::to_string(scene->solid->n_dofs()));
    // Each process's unknowns come in another order on a distributed mesh.
    const bool distributed
      = !geometry::holds_whole_mesh<dim>(scene->triangulation);
    const auto kind
      = [](const bool d) { return std::string(d ? "distributed" : "shared"); };
    require(checkpoint.distributed_mesh == distributed,
            "--restart",
            "the checkpoint was written on a "
              + kind(checkpoint.distributed_mesh)
              + " mesh; this run's 'Geometry/Mesh distribution' gives a "
              + kind(distributed)
              + " one, whose processes order their "
                "unknowns otherwise: restart with the same setting");
    cut_back_files(checkpoint, appended_files());
    summary->resume();
    for (auto &[name, postprocessor] : postprocessors)
      {
        const auto found = checkpoint.postprocessor_state.find(name);
        postprocessor->restore(found == checkpoint.postprocessor_state.end()
                                 ? std::vector<std::string>()
                                 : found->second);
      }
    state.time = checkpoint.time;
    integrator->restore_scalars(checkpoint.integrator_scalars);
    parallel_tools::screen()
      << "tissuefem: continuing from the checkpoint at step " << checkpoint.step
      << ", t = " << state.time << std::endl;
    return checkpoint.step;
  }


  template <int dim>
  void
  Elasticity<dim>::postprocess(const unsigned int      step,
                               const time::StepReport &report,
                               const time::State      &state)
  {
    // Nothing of a state that is not finite is written.
    if (!all_finite(state.u) || !all_finite(state.v))
      throw SolverError("non-finite displacement or velocity at t = "
                        + std::to_string(state.time)
                        + "; nothing was written for this step");
    // One copy with ghost entries serves every postprocessor that
    // evaluates the displacement field.
    VectorType u_ghosted;
    scene->discretization->initialize_vector(u_ghosted, true);
    u_ghosted = state.u;
    // The obstacles' reports once per state, for the tools and the
    // postprocessors alike (every process calls: they sum over them).
    const contact::Reports<dim> reports
      = scene->obstacle_contact
          ? scene->obstacle_contact->report(u_ghosted, state.time)
          : contact::Reports<dim>();
    const postprocess::Step<dim> current{
      step, report, state, u_ghosted, reports};
    for (auto &[name, postprocessor] : postprocessors)
      postprocessor->execute(current);
  }


  template <int dim>
  void
  Elasticity<dim>::wait_for_postprocessors(TimerOutput       &timer,
                                           const time::State &state)
  {
    // Timed apart: a paused or paced run is not slow output.
    TimerOutput::Scope scope(timer, "waiting (live view: paused, paced)");
    for (auto &[name, postprocessor] : postprocessors)
      postprocessor->wait(state);
  }


  template <int dim>
  void
  Elasticity<dim>::adapt_mesh(const unsigned int step, time::State &state)
  {
    if (!adaptation->due(step))
      return;
    // The solid announces the change to the solver, the integrator, the
    // state's boundary values and the postprocessors.
    if (adaptation->adapt(
          state.u, state.time, time_parameters.time_step, state_vectors(state)))
      parallel_tools::screen()
        << "  mesh adapted: " << scene->triangulation.n_global_active_cells()
        << " cells, " << scene->solid->n_dofs() << " unknowns" << std::endl;
  }


  namespace
  {
    /// Contact's share of the steps' wall time, its median and 95th
    /// percentile per step; empty without contact.
    std::string
    contact_time_report(const postprocess::RunTotals &totals)
    {
      std::vector<double> contact = totals.contact_seconds;
      const double        in_contact
        = std::accumulate(contact.begin(), contact.end(), 0.);
      if (!(in_contact > 0))
        return {};
      const double all = std::accumulate(totals.step_seconds.begin(),
                                         totals.step_seconds.end(),
                                         0.);
      std::sort(contact.begin(), contact.end());
      const auto at = [&](const double q) {
        return contact[std::min<std::size_t>(contact.size() - 1,
                                             q * contact.size())];
      };
      std::ostringstream s;
      s << std::setprecision(3) << "contact (detection, assembly, energies, "
        << "multiplier updates): " << 100 * in_contact / all
        << " % of the steps' wall time; per step median " << 1e3 * at(0.5)
        << " ms, 95th percentile " << 1e3 * at(0.95)
        << " ms (statistics.csv: contact_seconds)";
      return s.str();
    }


    /// What the solid holds by part, per cell, beside the peak: what the
    /// rest of the peak is (libraries, vectors, the linear solver) follows.
    template <int dim>
    std::string
    memory_parts_report(const postprocess::RunTotals &totals,
                        const Triangulation<dim>     &triangulation)
    {
      const double       cells = triangulation.n_global_active_cells();
      double             sum   = 0;
      std::ostringstream s;
      s << std::setprecision(3)
        << "memory the solid holds at the end (bytes per cell):";
      const char *separator = " ";
      for (const auto &[part, bytes] : totals.memory_parts)
        {
          s << separator << part << ' ' << bytes / cells;
          separator = ", ";
          sum += bytes;
        }
      s << "; together " << sum / 1e6 << " MB of the peak "
        << totals.peak_bytes / 1e6
        << " MB (the rest: libraries, vectors, linear solver)";
      return s.str();
    }


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
  bool
  Elasticity<dim>::take_step(time::State &state, time::StepReport &report)
  {
    const double end_time = time_parameters.end_time;
    // A live tool: positions must cover the step before it starts.
    for (auto &[name, tool] : scene->tools)
      if (!tool->synchronize(
            std::min(state.time + time_parameters.time_step, end_time)))
        {
          parallel_tools::screen() << "live session ended at t = " << state.time
                                   << ": " << tool->live_end() << std::endl;
          return false;
        }
    move_tool(state);
    const double contact = scene->solid->contribution_seconds();
    const auto   start   = std::chrono::steady_clock::now();
    report               = integrator->advance(state, end_time);
    report.step_seconds
      = std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
    report.contact_seconds = scene->solid->contribution_seconds() - contact;
    return true;
  }


  template <int dim>
  void
  Elasticity<dim>::finish(const time::State      &state,
                          postprocess::RunTotals &totals)
  {
    auto                          &screen = parallel_tools::screen();
    Utilities::System::MemoryStats memory;
    Utilities::System::get_memory_stats(memory);
    totals.peak_bytes = Utilities::MPI::sum(1024. * memory.VmHWM,
                                            parallel_tools::communicator());
    totals.peak_bytes_largest
      = Utilities::MPI::max(1024. * memory.VmHWM,
                            parallel_tools::communicator());
    totals.memory_parts.clear();
    for (const auto &[part, bytes] : scene->solid->memory_parts())
      totals.memory_parts.emplace_back(
        part,
        Utilities::MPI::sum(static_cast<double>(bytes),
                            parallel_tools::communicator()));
    output::RunRecord record;
    // What adaptation made of the mesh, for regression tests that must see
    // refinement that stopped: the finest level and whether there are
    // hanging nodes. Not the cell count: where the indicator vanishes (the
    // exact solutions of the adaptive tests) round-off breaks the ties, and
    // the count moves with the number of threads (91 or 106 cells).
    if (adaptation->enabled())
      summary->line("final mesh: finest level "
                    + std::to_string(scene->triangulation.n_levels() - 1)
                    + (scene->solid->get_discretization().has_hanging_nodes
                         ? ", hanging nodes"
                         : ", no hanging nodes"));
    for (auto &[name, postprocessor] : postprocessors)
      postprocessor->finish(state, totals, record);
    screen << "peak memory (resident, all processes): "
           << totals.peak_bytes / 1e6 << " MB, "
           << totals.peak_bytes / scene->solid->n_dofs()
           << " bytes per unknown, "
           << totals.peak_bytes / scene->triangulation.n_global_active_cells()
           << " bytes per cell; the largest process "
           << totals.peak_bytes_largest / 1e6 << " MB" << std::endl;
    screen << memory_parts_report(totals, scene->triangulation) << std::endl;
    if (const std::string s = integrator->summary(); !s.empty())
      screen << s << std::endl;
    screen << real_time_report(totals.step_seconds,
                               time_parameters.real_time_budget,
                               state.time)
           << std::endl;
    if (const std::string s = contact_time_report(totals); !s.empty())
      screen << s << std::endl;
    if (parallel_tools::is_root())
      record.write(output_parameters.directory + "/run.txt");
    const auto &linear = linear_solver->statistics();
    screen << "linear solver: " << linear.solves << " solves, "
           << linear.iterations << " Krylov iterations, " << linear.setups
           << " symbolic factorizations or AMG builds (" << linear.setup_seconds
           << " s), " << linear.factorizations << " numeric factorizations"
           << std::endl;
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
    auto         &screen = parallel_tools::screen();
    auto         &solid  = *scene->solid;
    time::Context context{solid,
                          time_parameters,
                          newton_parameters,
                          *linear_solver};
    time::State   state = scene->initial_state();
    if (scene->obstacle_contact)
      {
        VectorType ghosted;
        scene->discretization->initialize_vector(ghosted, true);
        ghosted = state.u;
        scene->obstacle_contact->check_start(ghosted, state.time);
      }
    const auto follow_changes = connect_to_changes(state);
    move_tool(state);
    // The integrator may still reject its input (an explicit step above
    // the critical one): before any file exists.
    integrator->initialize(context, state);
    // Once started, the integrator rebuilds its work vectors and masses
    // after each change, last, when the state is on the new mesh and
    // constraints.
    const boost::signals2::scoped_connection restart_integrator
      = solid.signals.changed.connect([this]() { integrator->mesh_changed(); });
    unsigned int step = start_outputs(state);

    screen << "tissuefem: " << dim << "D elasticity, " << scene->describe()
           << ", integrator '" << time_parameters.integrator
           << "', linear solver '" << linear_solver->name() << "'\n"
           << geometry::describe_boundary_ids(scene->triangulation) << '\n';
    if (const std::string s = scene->describe_distribution(); !s.empty())
      screen << s << '\n';
    screen << scene->boundary_conditions->describe_load_factor() << std::endl;
    for (const auto &line : scene->notes)
      screen << line << std::endl;
    // The table is printed at the end of a finished run, before the line
    // that says where the files went.
    TimerOutput timer(screen, TimerOutput::never, TimerOutput::wall_times);
    if (step == 0)
      {
        summary->line(
          "cells "
          + std::to_string(scene->triangulation.n_global_active_cells())
          + " unknowns " + std::to_string(solid.n_dofs()));
        postprocess(0, time::StepReport(), state);
        wait_for_postprocessors(timer, state);
      }

    postprocess::RunTotals totals;
    try
      {
        run_steps(state, step, timer, totals);
      }
    catch (const std::exception &e)
      {
        // Whoever watches the run (the live view's pages) learns why it
        // stopped; the caller reports it as before.
        for (auto &[name, postprocessor] : postprocessors)
          postprocessor->abort(e.what());
        throw;
      }
    totals.wall_seconds = std::chrono::duration<double>(
                            std::chrono::steady_clock::now() - run_start)
                            .count();
    finish(state, totals);
    timer.print_summary();
    screen << "output in " << output_parameters.directory
           << "/ (run.txt: the run's figures, with units)" << std::endl;
  }


  template <int dim>
  void
  Elasticity<dim>::run_steps(time::State            &state,
                             unsigned int           &step,
                             TimerOutput            &timer,
                             postprocess::RunTotals &totals)
  {
    auto        &screen   = parallel_tools::screen();
    const double end_time = time_parameters.end_time;
    while (state.time < end_time * (1 - 1e-12))
      {
        time::StepReport report;
        {
          TimerOutput::Scope scope(timer, "time steps (integrator)");
          if (!take_step(state, report))
            break;
        }
        ++step;
        totals.step_seconds.push_back(report.step_seconds);
        totals.contact_seconds.push_back(report.contact_seconds);
        totals.assembly_seconds += report.assembly_seconds;
        totals.solve_seconds += report.solve_seconds;
        totals.newton_iterations += report.newton_iterations;
        totals.rejected_attempts += report.rejected_attempts;
        {
          TimerOutput::Scope scope(timer, "output");
          screen << "step " << std::setw(5) << step << "  t = " << std::setw(10)
                 << state.time << "  dt = " << std::setw(10) << report.dt
                 << "  Newton " << std::setw(2) << report.newton_iterations
                 << "  |R| = " << std::scientific << std::setprecision(2)
                 << report.residual_norm << std::defaultfloat
                 << std::setprecision(6) << std::endl;
          postprocess(step, report, state);
          // Due and possible (the mouse may hold the tissue now: the
          // last checkpoint then stays).
          const unsigned int interval = output_parameters.checkpoint_interval;
          if (interval > 0 && step % interval == 0
              && checkpoint_obstacle().empty())
            write_checkpoint(step, state);
        }
        wait_for_postprocessors(timer, state);
        TimerOutput::Scope scope(timer, "output");
        stop_if_interrupted(step, state);
        // The state just written is an equilibrium (or solution) on its
        // mesh; the next step starts on the adapted one.
        if (state.time < end_time * (1 - 1e-12))
          adapt_mesh(step, state);
      }
  }

  template class Elasticity<1>;
  template class Elasticity<2>;
  template class Elasticity<3>;

  TISSUEFEM_REGISTER_PROBLEM(Elasticity,
                             "elasticity",
                             "a hyperelastic body under boundary conditions, "
                             "quasistatic or dynamic.")
} // namespace tissuefem::problems
