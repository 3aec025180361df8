#include <deal.II/base/data_out_base.h>
#include <deal.II/base/utilities.h>
#include <deal.II/numerics/data_component_interpretation.h>
#include <deal.II/numerics/data_out.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/output/output_writer.h>
#include <tissuefem/solid/quantities.h>

#include <filesystem>
#include <iomanip>
#include <sstream>

namespace tissuefem::output
{
  void
  OutputParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.declare_entry("Directory",
                      "output",
                      Patterns::Anything(),
                      "Directory (relative to the working directory) that "
                      "receives solution-*.pvtu/.vtu, solution.pvd, "
                      "statistics.csv, probes.csv and reactions.csv; created "
                      "if missing.");
    prm.declare_entry("VTU interval",
                      "1",
                      Patterns::Integer(0),
                      "Write the fields every this many steps (and at t = 0); "
                      "0 writes no VTU files.");
    prm.declare_entry("Probe points",
                      "",
                      Patterns::Anything(),
                      "Reference points 'x, y, z' separated by ';' at which "
                      "the displacement goes to probes.csv every step "
                      "(Dimension coordinates per point).");
    prm.declare_entry("Summary file",
                      "",
                      Patterns::Anything(),
                      "If not empty: a file (relative to the working "
                      "directory) receiving the probe displacements, "
                      "reaction forces and final elastic energy (and the "
                      "rest-shape report) without timings or iteration "
                      "counts, for regression tests. Its directory must "
                      "exist.");
    prm.declare_entry("Reaction boundary ids",
                      "",
                      Patterns::List(Patterns::Integer(0, 254)),
                      "Boundary ids whose reaction force goes to "
                      "reactions.csv every step: the force the prescribed "
                      "boundary applies to the body (force units), i.e. the "
                      "sum of the unconstrained nodal residual over the "
                      "boundary's nodes. A tool holding the boundary feels "
                      "the opposite force.");
    prm.declare_entry("Report rest shape",
                      "false",
                      Patterns::Bool(),
                      "At the end of the run, report (on screen and in the "
                      "summary file) the distance from the rest shape up to "
                      "a rigid motion (largest vertex distance after the best "
                      "rigid fit, length units) and the smallest J = det F: "
                      "the figures of an inversion-recovery test.");
    prm.declare_entry("Summary interval",
                      "1",
                      Patterns::Integer(1),
                      "Steps between rows of the summary file.");
    prm.declare_entry(
      "Checkpoint interval",
      "0",
      Patterns::Integer(0),
      "Steps between checkpoints written to '<Directory>/checkpoint' "
      "(atomically: a new one replaces the old one whole); 0: only when the "
      "run is interrupted by SIGINT or SIGTERM. 'tissuefem FILE.prm "
      "--restart <Directory>/checkpoint' continues the run; its outputs are "
      "then those of an uninterrupted run, bit for bit except the "
      "wall-clock columns of statistics.csv (same FILE.prm and "
      "process count; quasistatic, backward Euler, and damped central "
      "difference without active region; no tool or mesh adaptation).");
    prm.leave_subsection();
  }


  void
  OutputParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    directory           = prm.get("Directory");
    vtu_interval        = prm.get_integer("VTU interval");
    probe_points        = prm.get("Probe points");
    summary_file        = prm.get("Summary file");
    summary_interval    = prm.get_integer("Summary interval");
    report_rest_shape   = prm.get_bool("Report rest shape");
    checkpoint_interval = prm.get_integer("Checkpoint interval");
    reaction_boundary_ids.clear();
    for (const auto &id :
         Utilities::split_string_list(prm.get("Reaction boundary ids")))
      reaction_boundary_ids.push_back(Utilities::string_to_int(id));
    prm.leave_subsection();
    require(!directory.empty(), "Output/Directory", "must not be empty");
  }


  template <int dim>
  OutputWriter<dim>::OutputWriter(const OutputParameters  &parameters,
                                  const solid::Solid<dim> &solid)
      : parameters(parameters)
      , solid(solid)
  {
    const auto &d = solid.get_discretization();
    probes
      = std::make_unique<Probes<dim>>(parse_points<dim>(parameters.probe_points,
                                                        "Output/Probe points"),
                                      *d.mapping,
                                      d.dof_handler,
                                      "Output/Probe points");
  }


  namespace
  {
    const char *coordinate_names[]   = {"X", "Y", "Z"};
    const char *displacement_names[] = {"ux", "uy", "uz"};

    void
    open_or_fail(std::ofstream &stream, const std::string &path)
    {
      stream.open(path);
      require(static_cast<bool>(stream),
              "Output/Directory",
              "cannot write '" + path + "'");
      stream << std::setprecision(10);
    }

    /// Writes @p text to @p path whole: into a temporary file, then renamed.
    template <typename Writer>
    void
    write_whole(const std::string &path, const Writer &writer)
    {
      {
        std::ofstream file(path + ".tmp");
        writer(file);
      }
      std::filesystem::rename(path + ".tmp", path);
    }
  } // namespace


  template <int dim>
  void
  OutputWriter<dim>::open()
  {
    // Process 0 checks and creates; the others learn the outcome, so that
    // every process fails alike.
    std::string error;
    if (parallel_tools::is_root())
      try
        {
          // The summary file first: if it cannot be written, nothing is
          // created.
          if (!parameters.summary_file.empty())
            {
              summary.open(parameters.summary_file);
              require(static_cast<bool>(summary),
                      "Output/Summary file",
                      "cannot write '" + parameters.summary_file + "'");
              summary << std::setprecision(8);
            }
          std::error_code code;
          std::filesystem::create_directories(parameters.directory, code);
          require(!code,
                  "Output/Directory",
                  "cannot create '" + parameters.directory
                    + "': " + code.message());
          open_or_fail(statistics_file,
                       parameters.directory + "/statistics.csv");
          statistics_file
            << "step,time,dt,newton_iterations,linear_iterations,"
               "rejected_attempts,final_residual_norm,assembly_seconds,"
               "solve_seconds,step_seconds,substeps,jacobian_evaluations,"
               "stored_energy,kinetic_energy,damping_work\n";
          open_or_fail(probes_file, parameters.directory + "/probes.csv");
          probes_file << "time,probe";
          for (unsigned int d = 0; d < dim; ++d)
            probes_file << ',' << coordinate_names[d];
          for (unsigned int d = 0; d < dim; ++d)
            probes_file << ',' << displacement_names[d];
          probes_file << '\n' << std::flush;
          if (!parameters.reaction_boundary_ids.empty())
            {
              open_or_fail(reactions_file,
                           parameters.directory + "/reactions.csv");
              reactions_file << "time,boundary";
              for (unsigned int d = 0; d < dim; ++d)
                reactions_file << ",F" << coordinate_names[d];
              reactions_file << '\n' << std::flush;
            }
        }
      catch (const InputError &e)
        {
          error = e.what();
        }
    error = Utilities::MPI::broadcast(parallel_tools::communicator(), error);
    if (!error.empty())
      throw InputError(error);
  }


  template <int dim>
  void
  OutputWriter<dim>::fill_checkpoint(Checkpoint &checkpoint)
  {
    checkpoint.damping_work = damping_work_sum;
    checkpoint.pvd_records  = pvd_records;
    if (!parallel_tools::is_root())
      return;
    for (auto *stream :
         {&statistics_file, &probes_file, &reactions_file, &summary})
      if (stream->is_open())
        stream->flush();
    // (Root only: the sizes reach the other processes' checkpoint through
    // its file; no call here may throw.)
    for (const std::string &file : files())
      {
        std::error_code code;
        const auto      size        = std::filesystem::file_size(file, code);
        checkpoint.file_sizes[file] = code ? 0 : size;
      }
  }


  template <int dim>
  void
  OutputWriter<dim>::resume(const Checkpoint &checkpoint)
  {
    damping_work_sum = checkpoint.damping_work;
    pvd_records      = checkpoint.pvd_records;
    std::string error;
    if (parallel_tools::is_root())
      for (const std::string &file : files())
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
    if (!parallel_tools::is_root())
      return;
    const auto append = std::ios::out | std::ios::app;
    statistics_file.open(parameters.directory + "/statistics.csv", append);
    probes_file.open(parameters.directory + "/probes.csv", append);
    if (!parameters.reaction_boundary_ids.empty())
      reactions_file.open(parameters.directory + "/reactions.csv", append);
    for (auto *stream : {&statistics_file, &probes_file, &reactions_file})
      *stream << std::setprecision(10);
    if (!parameters.summary_file.empty())
      {
        summary.open(parameters.summary_file, append);
        summary << std::setprecision(8);
      }
  }


  template <int dim>
  std::vector<std::string>
  OutputWriter<dim>::files() const
  {
    std::vector<std::string> names = {parameters.directory + "/statistics.csv",
                                      parameters.directory + "/probes.csv"};
    if (!parameters.reaction_boundary_ids.empty())
      names.push_back(parameters.directory + "/reactions.csv");
    if (!parameters.summary_file.empty())
      names.push_back(parameters.summary_file);
    return names;
  }


  template <int dim>
  void
  OutputWriter<dim>::summary_line(const std::string &line)
  {
    if (summary.is_open())
      summary << line << '\n' << std::flush;
  }


  template <int dim>
  void
  OutputWriter<dim>::write_step(const unsigned int         step,
                                const time::StepReport    &s,
                                const time::State         &state,
                                const std::vector<double> &reactions,
                                const bool                 mesh_changed)
  {
    if (!all_finite(state.u) || !all_finite(state.v))
      throw SolverError("non-finite displacement or velocity at t = "
                        + std::to_string(state.time)
                        + "; nothing was written for this step");
    const auto &d = solid.get_discretization();
    if (mesh_changed)
      probes = std::make_unique<Probes<dim>>(probes->points(),
                                             *d.mapping,
                                             d.dof_handler,
                                             "Output/Probe points");
    VectorType u, v;
    d.initialize_vector(u, true);
    d.initialize_vector(v, true);
    u                 = state.u;
    v                 = state.v;
    const auto values = probes->evaluate(u);

    if (parallel_tools::is_root())
      {
        damping_work_sum += s.damping_work;
        if (step > 0)
          statistics_file << step << ',' << state.time << ',' << s.dt << ','
                          << s.newton_iterations << ',' << s.linear_iterations
                          << ',' << s.rejected_attempts << ','
                          << s.residual_norm << ',' << s.assembly_seconds << ','
                          << s.solve_seconds << ',' << s.step_seconds << ','
                          << s.substeps << ',' << s.jacobian_evaluations << ','
                          << s.stored_energy << ',' << s.kinetic_energy << ','
                          << damping_work_sum << std::endl;
        const bool summarize
          = summary.is_open() && step % parameters.summary_interval == 0;
        for (unsigned int p = 0; p < values.size(); ++p)
          {
            std::ostringstream row;
            row << std::setprecision(10) << state.time << ',' << p;
            for (unsigned int c = 0; c < dim; ++c)
              row << ',' << probes->points()[p][c];
            for (unsigned int c = 0; c < dim; ++c)
              row << ',' << values[p][c];
            probes_file << row.str() << '\n';
            if (summarize)
              {
                summary << "t = " << state.time << " probe " << p << " u =";
                for (unsigned int c = 0; c < dim; ++c)
                  summary << ' ' << values[p][c];
                summary << '\n';
              }
          }
        probes_file << std::flush;
        for (unsigned int b = 0; b < parameters.reaction_boundary_ids.size();
             ++b)
          {
            reactions_file << state.time << ','
                           << int(parameters.reaction_boundary_ids[b]);
            for (unsigned int c = 0; c < dim; ++c)
              reactions_file << ',' << reactions[b * dim + c];
            reactions_file << '\n';
            if (summarize)
              {
                summary << "t = " << state.time << " boundary "
                        << int(parameters.reaction_boundary_ids[b])
                        << " reaction =";
                for (unsigned int c = 0; c < dim; ++c)
                  summary << ' ' << reactions[b * dim + c];
                summary << '\n';
              }
          }
        reactions_file << std::flush;
        if (summarize)
          summary << std::flush;
      }

    if (parameters.vtu_interval > 0 && step % parameters.vtu_interval == 0)
      write_vtu(step, state.time, u, v);
  }


  template <int dim>
  void
  OutputWriter<dim>::write_vtu(const unsigned int step,
                               const double       time,
                               const VectorType  &u,
                               const VectorType  &v)
  {
    const auto &d = solid.get_discretization();
    const std::vector<DataComponentInterpretation::DataComponentInterpretation>
      vector_field(dim,
                   DataComponentInterpretation::component_is_part_of_vector);

    Vector<float> jacobian, von_mises;
    solid::cell_fields(
      d, solid.get_materials(), solid.fibres(), u, jacobian, von_mises);
    const bool finite
      = Utilities::MPI::min((all_finite(jacobian) && all_finite(von_mises)) ? 1
                                                                            : 0,
                            parallel_tools::communicator());
    if (!finite)
      throw SolverError("non-finite J or stress at step " + std::to_string(step)
                        + "; VTU file not written");
    const auto   &triangulation = d.dof_handler.get_triangulation();
    Vector<float> material_id(triangulation.n_active_cells());
    Vector<float> process(triangulation.n_active_cells());
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        material_id[cell->active_cell_index()] = cell->material_id();
        process[cell->active_cell_index()]     = cell->subdomain_id();
      }

    DataOut<dim> data_out;
    data_out.attach_dof_handler(d.dof_handler);
    data_out.add_data_vector(u,
                             std::vector<std::string>(dim, "displacement"),
                             DataOut<dim>::type_dof_data,
                             vector_field);
    data_out.add_data_vector(v,
                             std::vector<std::string>(dim, "velocity"),
                             DataOut<dim>::type_dof_data,
                             vector_field);
    data_out.add_data_vector(jacobian, "J");
    data_out.add_data_vector(von_mises, "von_Mises_Cauchy_stress");
    data_out.add_data_vector(material_id, "material_id");
    data_out.add_data_vector(process, "process");
    const std::vector<Vector<float>> fibre
      = solid.fibres().cell_averages(triangulation.n_active_cells());
    static const char *fibre_names[] = {"fibre_x", "fibre_y", "fibre_z"};
    for (unsigned int c = 0; c < fibre.size(); ++c)
      data_out.add_data_vector(fibre[c], fibre_names[c]);
    data_out.build_patches(*d.mapping, d.fe->degree);

    // One piece per process, a .pvtu naming them, and the .pvd series.
    std::ostringstream base;
    base << "solution-" << std::setw(5) << std::setfill('0') << step;
    const unsigned int rank
      = Utilities::MPI::this_mpi_process(parallel_tools::communicator());
    const std::string piece = base.str() + "." + std::to_string(rank) + ".vtu";
    write_whole(parameters.directory + "/" + piece,
                [&](std::ostream &out) { data_out.write_vtu(out); });
    if (!parallel_tools::is_root())
      return;
    std::vector<std::string> pieces;
    for (unsigned int p = 0; p < parallel_tools::n_processes(); ++p)
      pieces.push_back(base.str() + "." + std::to_string(p) + ".vtu");
    const std::string master = base.str() + ".pvtu";
    write_whole(parameters.directory + "/" + master, [&](std::ostream &out) {
      data_out.write_pvtu_record(out, pieces);
    });
    pvd_records.emplace_back(time, master);
    write_whole(parameters.directory + "/solution.pvd", [&](std::ostream &out) {
      DataOutBase::write_pvd_record(out, pvd_records);
    });
  }

  template class OutputWriter<1>;
  template class OutputWriter<2>;
  template class OutputWriter<3>;
} // namespace tissuefem::output
