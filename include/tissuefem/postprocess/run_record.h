#pragma once

#include <tissuefem/postprocess/interface.h>

namespace tissuefem::postprocess
{
  /**
   * The run's size and cost in run.txt: processes and threads, cells and
   * unknowns at the end, steps, simulated time, Newton iterations and
   * rejected attempts (sums over steps), wall-clock seconds (total, steps,
   * assembly, solve; median, 95th percentile and largest step) and peak
   * resident memory (MB, summed over processes).
   */
  template <int dim>
  class RunRecordRows : public Interface<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &)
    {
    }

    explicit RunRecordRows(ParameterHandler &)
    {
    }


    void
    execute(const Step<dim> &) override
    {
    }

    void
    finish(const time::State &state,
           const RunTotals   &totals,
           output::RunRecord &record) override;

  private:
  };
} // namespace tissuefem::postprocess
