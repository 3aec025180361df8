#pragma once

#include <tissuefem/postprocess/interface.h>

#include <utility>

namespace tissuefem::postprocess
{
  /**
   * The fields for ParaView every 'Output/VTU/Interval' steps (and at t =
   * 0): solution-NNNNN.pvtu naming one solution-NNNNN.P.vtu piece per MPI
   * process, and the series solution.pvd. Fields: displacement and velocity
   * (length and length per time units), J = det F, the von Mises Cauchy
   * stress (stress units), material id, owning process and the fibre
   * direction where there is one. Every file is written to a temporary
   * name and renamed.
   */
  template <int dim>
  class VtuOutput : public Interface<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    explicit VtuOutput(ParameterHandler &prm);


    std::vector<std::string>
    save() const override;

    void
    restore(const std::vector<std::string> &lines) override;

    void
    execute(const Step<dim> &step) override;

  private:
    /// Writes the pieces, the .pvtu and the .pvd of step @p step.
    void
    write(const unsigned int step,
          const double       time,
          const VectorType  &u,
          const VectorType  &v);

    unsigned int interval = 1;
    /// (time, .pvtu file) of every step written so far: the .pvd series.
    std::vector<std::pair<double, std::string>> records;
  };
} // namespace tissuefem::postprocess
