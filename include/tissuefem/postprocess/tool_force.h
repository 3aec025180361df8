#pragma once

#include <tissuefem/postprocess/interface.h>

#include <fstream>
#include <vector>

namespace tissuefem::postprocess
{
  /**
   * With tools, after every step, from what each tool reports
   * (tool::Record):
   * - tool_force.csv: time, whether the tool acts on the tissue ('holding',
   *   0 or 1), its displacement d(t) (length units) and the force the
   *   tissue exerts on it (force units);
   * - haptic_force.csv: the forces sent to a haptic device between the
   *   steps (time, force, and 'error', the distance from the force the
   *   simulation then computed, force units);
   * - the summary file: 't = T tool force = ...' every step;
   * - at the end of the run, the tool's report (haptic updates, share
   *   within the haptic budget, extrapolation error).
   * With several tools each has its own pair of files, tool_force-NAME.csv
   * and haptic_force-NAME.csv (NAME: the tool's registered name, spaces as
   * '_'), and its summary lines say 'tool force (NAME)'.
   * Process 0 writes; rows are flushed every step, so a live session that
   * ends abruptly leaves whole rows.
   */
  template <int dim>
  class ToolForce : public Interface<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &)
    {
    }

    explicit ToolForce(ParameterHandler &)
    {
    }

    /// Creates the two files and lets the tool open its device link.
    void
    open() override;

    std::vector<std::string>
    files() const override;

    void
    restore(const std::vector<std::string> &lines) override;

    void
    execute(const Step<dim> &step) override;

    void
    finish(const time::State &state,
           const RunTotals   &totals,
           output::RunRecord &record) override;

  private:
    /// Writes one step's rows of one tool.
    static void
    write(const tool::Record<dim> &record,
          const double             time,
          std::ofstream           &force,
          std::ofstream           &haptic);

    /// Per tool, in the order of files(): its tool_force and haptic_force
    /// files (process 0).
    std::vector<std::ofstream> streams;
  };
} // namespace tissuefem::postprocess
