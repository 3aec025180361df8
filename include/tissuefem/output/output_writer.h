#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/output/checkpoint.h>
#include <tissuefem/output/probes.h>
#include <tissuefem/solid/solid.h>
#include <tissuefem/time/interface.h>

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
    unsigned int                    checkpoint_interval;
  };

  /**
   * Writes a run's results into the output directory:
   * - solution-NNNNN.pvtu (one solution-NNNNN.P.vtu piece per MPI
   *   process) and solution.pvd: displacement, velocity, J, von Mises
   *   stress, material id and owning process, every 'VTU interval' steps;
   * - statistics.csv: one row per step: time (time units), dt (the
   *   step, or the interval an adaptive integrator covered with
   *   'substeps' steps of its own), Newton and Krylov iterations,
   *   rejected attempts, final residual norm (force units), wall times
   *   (s) of assembly, solve and the whole step, Jacobian evaluations,
   *   stored and kinetic energy of the state (energy units) and the energy
   *   dissipated by the integrator's damping since t = 0;
   * - probes.csv: displacement at the probe points, long form, every step;
   * - reactions.csv: force through each 'Reaction boundary ids' boundary;
   * - the optional summary file: probe values and energy without timings,
   *   for regression tests.
   * Files are created only by open(), after all input has been checked;
   * every VTU/PVD file is written to a temporary name and renamed, and CSV
   * rows are flushed whole, so an interrupted run leaves no partial file.
   * Process 0 writes every file but the VTU pieces; every process must call
   * every function (they gather values).
   */
  template <int dim>
  class OutputWriter
  {
  public:
    OutputWriter(const OutputParameters  &parameters,
                 const solid::Solid<dim> &solid);

    /// Creates the directory and files.
    void
    open();

    /**
     * Writes step @p step (0: the initial state) with what the integrator
     * reported; @p reactions holds dim components per 'Reaction boundary
     * ids' entry. Rebuilds the probes if the mesh changed since the last
     * call (@p mesh_changed).
     */
    void
    write_step(const unsigned int         step,
               const time::StepReport    &report,
               const time::State         &state,
               const std::vector<double> &reactions,
               const bool                 mesh_changed = false);

    /// Writes a free-form line to the summary file (if any).
    void
    summary_line(const std::string &line);

    /// What the writer carries from step to step, and the sizes of the
    /// files it appends to, for a checkpoint.
    void
    fill_checkpoint(Checkpoint &checkpoint);

    /// Instead of open() when a run continues from @p checkpoint: the
    /// files are cut back to their sizes then and appended to.
    void
    resume(const Checkpoint &checkpoint);

  private:
    OutputParameters             parameters;
    const solid::Solid<dim>     &solid;
    std::unique_ptr<Probes<dim>> probes;
    std::ofstream statistics_file, probes_file, reactions_file, summary;
    /// Energy dissipated by the integrator's damping since the start.
    double                                      damping_work_sum = 0;
    std::vector<std::pair<double, std::string>> pvd_records;

    /// The files appended to step by step.
    std::vector<std::string>
    files() const;

    void
    write_vtu(const unsigned int step,
              const double       time,
              const VectorType  &u,
              const VectorType  &v);
  };
} // namespace tissuefem::output
