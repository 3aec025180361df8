#pragma once

#include <deal.II/base/parameter_handler.h>

#include <tissuefem/base/registry.h>
#include <tissuefem/output/run_record.h>
#include <tissuefem/output/summary_file.h>
#include <tissuefem/scene/scene.h>
#include <tissuefem/time/interface.h>

#include <memory>
#include <string>
#include <vector>

namespace tissuefem::postprocess
{
  using namespace dealii;

  /// What a postprocessor may look at besides its own parameters.
  template <int dim>
  struct Context
  {
    /// The body, its loads and constraints, its solid and tool.
    const Scene<dim> &scene;
    /// 'Output/Directory' (created before open()).
    std::string directory;
    /// The optional summary file for regression tests.
    output::SummaryFile &summary;
    /// The parameter file the run reads, as given on the command line.
    std::string parameter_file = {};
  };

  /// One state to process.
  template <int dim>
  struct Step
  {
    /// 0 for the initial state, then the number of steps taken.
    unsigned int number;
    /// What the integrator reported (empty for step 0).
    const time::StepReport &report;
    const time::State      &state;
    /// state.u with the ghost entries of this process's cells (point
    /// values, fields, errors need them).
    const VectorType &u_ghosted;
    /// Each obstacle's force, penetration, area and pressures at this
    /// state (empty without obstacles), computed once for every tool and
    /// postprocessor that reports them.
    const contact::Reports<dim> &contact;
  };

  /// What the whole run cost, for the end-of-run reports.
  struct RunTotals
  {
    /// Wall-clock seconds of each step.
    std::vector<double> step_seconds;
    /// Wall-clock seconds of each step spent in contact (force
    /// contributions).
    std::vector<double> contact_seconds;
    double              assembly_seconds = 0, solve_seconds = 0;
    unsigned int        newton_iterations = 0, rejected_attempts = 0;
    /// Resident memory, summed over processes (bytes).
    double peak_bytes = 0;
    /// The largest process's resident memory (bytes): what one machine's
    /// share of a run needs, which 'Geometry/Mesh distribution' lowers.
    double peak_bytes_largest = 0;
    /// What the solid holds at the end, by part (Solid::memory_parts()),
    /// summed over processes (bytes).
    std::vector<std::pair<std::string, double>> memory_parts;
    /// Wall-clock seconds from set-up to the end of the steps.
    double wall_seconds = 0;
  };

  /**
   * Something written from each state of a run: a file per step (VTU), a
   * row per step (CSV files), lines of the summary file, entries of the
   * run record. Each postprocessor is one file pair deriving from this
   * class, declares its own parameters (in the 'Output' subsection) and
   * registers itself with TISSUEFEM_REGISTER_POSTPROCESSOR; every
   * registered postprocessor runs, in alphabetical order of the names,
   * and writes only what its parameters ask for.
   *
   * Every process calls every function (postprocessors gather values);
   * only process 0 writes the shared files. Files are created by open(),
   * after all input has been checked; each row is written whole.
   *
   * Checkpoint and restart: files() names the files a postprocessor
   * appends to (the checkpoint records their sizes and a restart cuts them
   * back), and save()/restore() carry what it accumulates between steps.
   */
  template <int dim>
  class Interface
  {
  public:
    virtual ~Interface() = default;

    /// Keeps @p c (which outlives the postprocessor) as 'context'. A
    /// postprocessor that checks its parameters against the scene
    /// overrides this and calls it first. No file is written yet.
    virtual void
    initialize(const Context<dim> &c)
    {
      context = &c;
    }

    /// Creates its files (a run from t = 0).
    virtual void
    open()
    {
    }

    /// The files it appends to step by step.
    virtual std::vector<std::string>
    files() const
    {
      return {};
    }

    /// What it carries from step to step (lines without line breaks;
    /// doubles through output::exact_text).
    virtual std::vector<std::string>
    save() const
    {
      return {};
    }

    /// Instead of open() when a run continues from a checkpoint: takes back
    /// what save() gave and reopens its files (already cut back) to append.
    virtual void
    restore(const std::vector<std::string> & /*lines*/)
    {
    }

    /// Processes a state: the initial one (step 0) and each step's.
    virtual void
    execute(const Step<dim> &step)
      = 0;

    /// After every postprocessor has processed the state @p state, outside
    /// the outputs' timing: a postprocessor that holds the run (the live
    /// view pausing, or pacing it to the wall clock) waits here.
    virtual void
    wait(const time::State & /*state*/)
    {
    }

    /// When the run stops on an error (@p what says which), instead of
    /// finish(): a postprocessor that talks to someone tells them (the live
    /// view's pages). Files are already whole.
    virtual void
    abort(const std::string & /*what*/)
    {
    }

    /// At the end of the run, after the last step: adds entries to the run
    /// record (run.txt) and prints its report, if any.
    virtual void
    finish(const time::State & /*state*/,
           const RunTotals & /*totals*/,
           output::RunRecord & /*record*/)
    {
    }

  protected:
    /// What initialize() was given.
    const Context<dim> *context = nullptr;
  };

  template <int dim>
  using PostprocessorRegistry = Registry<Interface<dim>, ParameterHandler &>;
} // namespace tissuefem::postprocess

/**
 * Registers the postprocessor template @p Class (on dim) under @p name for
 * dim = 1, 2, 3, inside namespace tissuefem::postprocess at the end of its
 * source file. @p Class<dim> has a static declare_parameters(
 * ParameterHandler &) and a constructor taking ParameterHandler &.
 */
#define TISSUEFEM_REGISTER_POSTPROCESSOR(Class, name, description)     \
  namespace                                                            \
  {                                                                    \
    template <int dim>                                                 \
    bool tissuefem_register_postprocessor_##Class()                    \
    {                                                                  \
      PostprocessorRegistry<dim>::instance().add(                      \
        name,                                                          \
        description,                                                   \
        &Class<dim>::declare_parameters,                               \
        [](ParameterHandler &prm) -> std::unique_ptr<Interface<dim>> { \
          return std::make_unique<Class<dim>>(prm);                    \
        });                                                            \
      return true;                                                     \
    }                                                                  \
    const bool tissuefem_registered_postprocessor_##Class              \
      = tissuefem_register_postprocessor_##Class<1>()                  \
        && tissuefem_register_postprocessor_##Class<2>()               \
        && tissuefem_register_postprocessor_##Class<3>();              \
  }
