#pragma once

#include <tissuefem/problems/interface.h>
#include <tissuefem/study/picker.h>
#include <tissuefem/study/quantity.h>
#include <tissuefem/study/report.h>
#include <tissuefem/study/runner.h>
#include <tissuefem/study/variants.h>

#include <chrono>
#include <string>
#include <vector>

namespace tissuefem::study
{
  /**
   * 'Problem = study': runs one elasticity scene over a set of variants
   * (the Cartesian product of 'Study/Axes'), each as a tissuefem child
   * process in '<Study/Directory>/variant-K', and records for each its
   * size, wall times, memory and error in a quantity of interest; writes
   * results.csv, convergence tables with observed orders, gnuplot charts
   * (error against unknowns and against wall time, with the Pareto front)
   * and a summary; then optionally picks the cheapest variant that meets
   * an error tolerance and a step budget, and runs the scene with it.
   * Finished variants are kept: running the study again resumes it.
   *
   * Not a template on dim, unlike the other problems: the study itself
   * computes nothing in space; each variant is a process of its own.
   */
  class Study : public problems::Interface
  {
  public:
    Study(ParameterHandler &prm, const problems::RunContext &context);

    static void
    declare_parameters(ParameterHandler &prm);

    void
    setup() override;

    void
    run() override;

  private:
    problems::RunContext context;
    std::string          scene, directory, runs_directory, launcher, title;
    std::vector<study::Setting> settings;
    std::vector<study::Axis>    axes;
    unsigned int                rate_axis;
    std::string                 rates_against;
    std::vector<double>         tolerances;
    unsigned int                threads;
    study::QuantityParameters   quantity;
    study::PickerParameters     picker;
    std::vector<study::Variant> variants;
    /// 'Dimension' of the scene (of its first variant), for orders in h.
    unsigned int scene_dimension = 3;

    /// The run the errors are measured against ('Reference settings').
    study::Variant
    reference_variant() const;

    /// The --set arguments of a run with @p extra settings into @p output.
    std::vector<std::string>
    arguments(const std::vector<study::Setting> &extra,
              const std::string                 &output) const;

    /**
     * Runs the scene with @p extra settings as a child process into a
     * fresh @p output (described as @p what in messages). Throws
     * InputError if the executable cannot start, Interrupted if a signal
     * ended the run.
     */
    study::RunOutcome
    launch(const std::vector<study::Setting> &extra,
           const std::string                 &output,
           const std::string                 &what) const;

    /**
     * Runs (or, if it finished before with the same settings, reuses) one
     * variant in @p output; returns its row. Throws Interrupted if the run
     * was interrupted by a signal.
     */
    study::Row
    run_variant(const study::Variant &variant,
                const std::string    &output,
                bool                 &reused) const;

    // The phases of run(), in this order.

    /// 'Directory' and 'Runs directory'.
    void
    create_directories() const;

    /// Runs (or reuses) the reference run if the errors are measured
    /// against one; returns its directory, else an empty string.
    std::string
    run_reference() const;

    /// Runs (or reuses) every variant, printing progress and an estimate
    /// of the time left (from @p start); errors against the run in
    /// @p reference. Throws Interrupted between variants on a signal.
    std::vector<study::Row>
    run_variants(const std::string                          &reference,
                 const std::chrono::steady_clock::time_point start) const;

    /// results.csv, convergence.txt, the charts and summary.txt (also on
    /// the screen); @p what describes the quantity.
    void
    write_reports(const std::vector<study::Row> &rows,
                  const std::string             &what) const;

    /// The model choices for every tolerance and budget into choice.txt,
    /// and the runs of the chosen variants if 'Run choice' asks for them.
    void
    run_choices(const std::vector<study::Row> &rows,
                const std::string             &what) const;
  };
} // namespace tissuefem::study
