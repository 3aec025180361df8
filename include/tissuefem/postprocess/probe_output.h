#pragma once

#include <boost/signals2/connection.hpp>

#include <tissuefem/output/probes.h>
#include <tissuefem/postprocess/interface.h>

#include <fstream>
#include <memory>

namespace tissuefem::postprocess
{
  /**
   * probes.csv: the displacement (length units) at the 'Output/Probes/Points'
   * (reference coordinates) every step, long form (time, probe, X, Y[, Z],
   * ux, uy[, uz]); and in the summary file, every 'Summary interval' steps,
   * 't = T probe P u = ...'. The probes follow mesh changes (they listen to
   * the solid's changed signal).
   */
  template <int dim>
  class ProbeOutput : public Interface<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    explicit ProbeOutput(ParameterHandler &prm);

    void
    initialize(const Context<dim> &c) override;

    void
    open() override;

    std::vector<std::string>
    files() const override;

    void
    restore(const std::vector<std::string> &lines) override;

    void
    execute(const Step<dim> &step) override;

  private:
    /// Finds the probe points' cells on the current mesh.
    void
    locate();

    std::vector<Point<dim>>              points;
    std::unique_ptr<output::Probes<dim>> probes;
    boost::signals2::scoped_connection   follow_mesh;
    std::ofstream                        file;
  };
} // namespace tissuefem::postprocess
