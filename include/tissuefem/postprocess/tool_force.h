#pragma once

#include <tissuefem/postprocess/interface.h>

namespace tissuefem::postprocess
{
  /**
   * With a tool: after every step, the force the tissue exerts on it (force
   * units). The tool writes tool_force.csv and haptic_force.csv (see
   * tool/grasp_tool.h) and feeds its haptic extrapolation; the summary file
   * gets 't = T tool force = ...' every step; the end of the run the tool's
   * report (updates, share within the haptic budget, extrapolation error).
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


    /// Lets the tool create its files (and open its live link).
    void
    open() override;

    void
    execute(const Step &step) override;

    void
    finish(const time::State &state,
           const RunTotals   &totals,
           output::RunRecord &record) override;

  private:
  };
} // namespace tissuefem::postprocess
