#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/output/probes.h>
#include <tissuefem/solid/solid_system.h>

#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace tissuefem::output
{
  /// The 'Output' subsection.
  struct OutputParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    std::string                     directory;
    unsigned int                    vtu_interval;
    std::string                     probe_points;
    std::string                     summary_file;
    unsigned int                    summary_interval;
    std::vector<types::boundary_id> reaction_boundary_ids;
    bool                            report_rest_shape;
  };

  /// What one time step reports to statistics.csv and the screen.
  struct StepStatistics
  {
    unsigned int step;
    double       time, dt;
    unsigned int newton_iterations;
    double       residual_norm;
    double       assembly_seconds, solve_seconds;
  };

  /**
   * Writes a run's results into the output directory:
   * - solution-NNNNN.vtu and solution.pvd: displacement, velocity, J, von
   *   Mises stress and material id, every 'VTU interval' steps;
   * - statistics.csv: one row per step;
   * - probes.csv: displacement at the probe points, long form, every step;
   * - reactions.csv: force through each 'Reaction boundary ids' boundary;
   * - the optional summary file: probe values and energy without timings,
   *   for regression tests.
   * Files are created only by open(), after all input has been checked;
   * every VTU/PVD file is written to a temporary name and renamed, and CSV
   * rows are flushed whole, so an interrupted run leaves no partial file.
   */
  template <int dim>
  class OutputWriter
  {
  public:
    OutputWriter(const OutputParameters        &parameters,
                 const solid::SolidSystem<dim> &system);

    /// Creates the directory and files.
    void
    open();

    /// @p reactions holds one force per 'Reaction boundary ids' entry.
    void
    write_step(const StepStatistics              &statistics,
               const Vector<double>              &u,
               const Vector<double>              &v,
               const std::vector<Tensor<1, dim>> &reactions);

    /// Writes a free-form line to the summary file (if any).
    void
    summary_line(const std::string &line);

  private:
    OutputParameters               parameters;
    const solid::SolidSystem<dim> &system;
    std::unique_ptr<Probes<dim>>   probes;
    std::ofstream statistics_file, probes_file, reactions_file, summary;
    std::vector<std::pair<double, std::string>> pvd_records;

    void
    write_vtu(const unsigned int    step,
              const double          time,
              const Vector<double> &u,
              const Vector<double> &v);
  };
} // namespace tissuefem::output
