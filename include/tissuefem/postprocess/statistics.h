#pragma once

#include <tissuefem/postprocess/interface.h>

#include <fstream>

namespace tissuefem::postprocess
{
  /**
   * statistics.csv: one row per step: step, time (time units), dt (the step,
   * or the interval an adaptive integrator covered with 'substeps' steps of
   * its own), Newton and Krylov iterations, rejected attempts, final
   * residual norm (force units), wall times (s) of assembly, solve and the
   * whole step, Jacobian evaluations, stored and kinetic energy of the state
   * (energy units) and the energy dissipated by the integrator's damping
   * since t = 0 (energy units).
   */
  template <int dim>
  class Statistics : public Interface<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &)
    {
    }

    explicit Statistics(ParameterHandler &)
    {
    }


    void
    open() override;

    std::vector<std::string>
    files() const override;

    std::vector<std::string>
    save() const override;

    void
    restore(const std::vector<std::string> &lines) override;

    void
    execute(const Step<dim> &step) override;

  private:
    std::ofstream file;
    /// Energy dissipated by the integrator's damping since t = 0.
    double damping_work = 0;
  };
} // namespace tissuefem::postprocess
