#pragma once

#include <tissuefem/postprocess/interface.h>

#include <fstream>

namespace tissuefem::postprocess
{
  /**
   * With a tool, after every step, from what the tool reports
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
    execute(const Step &step) override;

    void
    finish(const time::State &state,
           const RunTotals   &totals,
           output::RunRecord &record) override;

  private:
    std::ofstream force_file, haptic_file;
  };
} // namespace tissuefem::postprocess
