#pragma once

#include <tissuefem/postprocess/interface.h>

namespace tissuefem::postprocess
{
  /**
   * The end state's figures: its stored energy int Psi dV and kinetic
   * energy 1/2 v.M v (energy units) into run.txt; 'final elastic energy'
   * into the summary file and on screen; and, if 'Output/Final state/Report
   * rest shape', the distance from the rest shape up to a rigid motion (largest
   * vertex distance after the best rigid fit, length units) and the
   * smallest J = det F: the figures of an inversion-recovery test.
   */
  template <int dim>
  class FinalState : public Interface<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    explicit FinalState(ParameterHandler &prm);


    void
    execute(const Step<dim> &) override
    {
    }

    void
    finish(const time::State &state,
           const RunTotals   &totals,
           output::RunRecord &record) override;

  private:
    bool report_rest_shape = false;
  };
} // namespace tissuefem::postprocess
