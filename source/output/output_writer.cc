#include <deal.II/base/data_out_base.h>
#include <deal.II/base/utilities.h>
#include <deal.II/numerics/data_component_interpretation.h>
#include <deal.II/numerics/data_out.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/output/output_writer.h>

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
                      "receives solution-*.vtu, solution.pvd, statistics.csv, "
                      "probes.csv and reactions.csv; created if missing.");
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
    prm.leave_subsection();
  }


  void
  OutputParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    directory         = prm.get("Directory");
    vtu_interval      = prm.get_integer("VTU interval");
    probe_points      = prm.get("Probe points");
    summary_file      = prm.get("Summary file");
    summary_interval  = prm.get_integer("Summary interval");
    report_rest_shape = prm.get_bool("Report rest shape");
    reaction_boundary_ids.clear();
    for (const auto &id :
         Utilities::split_string_list(prm.get("Reaction boundary ids")))
      reaction_boundary_ids.push_back(Utilities::string_to_int(id));
    prm.leave_subsection();
    require(!directory.empty(), "Output/Directory", "must not be empty");
  }


  template <int dim>
  OutputWriter<dim>::OutputWriter(const OutputParameters        &parameters,
                                  const solid::SolidSystem<dim> &system)
      : parameters(parameters)
      , system(system)
  {
    const auto &d = system.get_discretization();
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
  } // namespace


  template <int dim>
  void
  OutputWriter<dim>::open()
  {
    // The summary file first: if it cannot be written, nothing is created.
    if (!parameters.summary_file.empty())
      {
        summary.open(parameters.summary_file);
        require(static_cast<bool>(summary),
                "Output/Summary file",
                "cannot write '" + parameters.summary_file + "'");
        summary << std::setprecision(8);
      }
    std::error_code error;
    std::filesystem::create_directories(parameters.directory, error);
    require(!error,
            "Output/Directory",
            "cannot create '" + parameters.directory + "': " + error.message());
    open_or_fail(statistics_file, parameters.directory + "/statistics.csv");
    statistics_file << "step,time,dt,newton_iterations,final_residual_norm,"
                       "assembly_seconds,solve_seconds\n";
    open_or_fail(probes_file, parameters.directory + "/probes.csv");
    probes_file << "time,probe";
    for (unsigned int d = 0; d < dim; ++d)
      probes_file << ',' << coordinate_names[d];
    for (unsigned int d = 0; d < dim; ++d)
      probes_file << ',' << displacement_names[d];
    probes_file << '\n' << std::flush;
    if (!parameters.reaction_boundary_ids.empty())
      {
        open_or_fail(reactions_file, parameters.directory + "/reactions.csv");
        reactions_file << "time,boundary";
        for (unsigned int d = 0; d < dim; ++d)
          reactions_file << ",F" << coordinate_names[d];
        reactions_file << '\n' << std::flush;
      }
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
  OutputWriter<dim>::write_step(const StepStatistics              &s,
                                const Vector<double>              &u,
                                const Vector<double>              &v,
                                const std::vector<Tensor<1, dim>> &reactions)
  {
    if (!all_finite(u) || !all_finite(v))
      throw SolverError("non-finite displacement or velocity at t = "
                        + std::to_string(s.time)
                        + "; nothing was written for this step");
    if (s.step > 0)
      statistics_file << s.step << ',' << s.time << ',' << s.dt << ','
                      << s.newton_iterations << ',' << s.residual_norm << ','
                      << s.assembly_seconds << ',' << s.solve_seconds
                      << std::endl;

    const auto values = probes->evaluate(u);
    const bool summarize
      = summary.is_open() && s.step % parameters.summary_interval == 0;
    for (unsigned int p = 0; p < values.size(); ++p)
      {
        std::ostringstream row;
        row << std::setprecision(10) << s.time << ',' << p;
        for (unsigned int d = 0; d < dim; ++d)
          row << ',' << probes->points()[p][d];
        for (unsigned int d = 0; d < dim; ++d)
          row << ',' << values[p][d];
        probes_file << row.str() << '\n';
        if (summarize)
          {
            summary << "t = " << s.time << " probe " << p << " u =";
            for (unsigned int d = 0; d < dim; ++d)
              summary << ' ' << values[p][d];
            summary << '\n';
          }
      }
    probes_file << std::flush;
    for (unsigned int b = 0; b < reactions.size(); ++b)
      {
        reactions_file << s.time << ','
                       << int(parameters.reaction_boundary_ids[b]);
        for (unsigned int d = 0; d < dim; ++d)
          reactions_file << ',' << reactions[b][d];
        reactions_file << '\n';
        if (summarize)
          {
            summary << "t = " << s.time << " boundary "
                    << int(parameters.reaction_boundary_ids[b])
                    << " reaction =";
            for (unsigned int d = 0; d < dim; ++d)
              summary << ' ' << reactions[b][d];
            summary << '\n';
          }
      }
    reactions_file << std::flush;
    if (summarize)
      summary << std::flush;

    if (parameters.vtu_interval > 0 && s.step % parameters.vtu_interval == 0)
      write_vtu(s.step, s.time, u, v);
  }


  template <int dim>
  void
  OutputWriter<dim>::write_vtu(const unsigned int    step,
                               const double          time,
                               const Vector<double> &u,
                               const Vector<double> &v)
  {
    const auto &d = system.get_discretization();
    const std::vector<DataComponentInterpretation::DataComponentInterpretation>
      vector_field(dim,
                   DataComponentInterpretation::component_is_part_of_vector);

    Vector<float> jacobian, von_mises;
    system.cell_fields(u, jacobian, von_mises);
    if (!all_finite(jacobian) || !all_finite(von_mises))
      throw SolverError("non-finite J or stress at step " + std::to_string(step)
                        + "; VTU file not written");
    const auto   &triangulation = d.dof_handler.get_triangulation();
    Vector<float> material_id(triangulation.n_active_cells());
    for (const auto &cell : triangulation.active_cell_iterators())
      material_id[cell->active_cell_index()] = cell->material_id();

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
    const std::vector<Vector<float>> fibre = system.cell_fibre_directions();
    static const char *fibre_names[]       = {"fibre_x", "fibre_y", "fibre_z"};
    for (unsigned int c = 0; c < fibre.size(); ++c)
      data_out.add_data_vector(fibre[c], fibre_names[c]);
    data_out.build_patches(*d.mapping, d.fe->degree);

    std::ostringstream name;
    name << "solution-" << std::setw(5) << std::setfill('0') << step << ".vtu";
    const std::string path = parameters.directory + "/" + name.str();
    {
      std::ofstream file(path + ".tmp");
      data_out.write_vtu(file);
    }
    std::filesystem::rename(path + ".tmp", path);

    pvd_records.emplace_back(time, name.str());
    const std::string pvd = parameters.directory + "/solution.pvd";
    {
      std::ofstream file(pvd + ".tmp");
      DataOutBase::write_pvd_record(file, pvd_records);
    }
    std::filesystem::rename(pvd + ".tmp", pvd);
  }

  template class OutputWriter<1>;
  template class OutputWriter<2>;
  template class OutputWriter<3>;
} // namespace tissuefem::output
