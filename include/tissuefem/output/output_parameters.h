#pragma once

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace tissuefem::output
{
  using namespace dealii;

  /**
   * The entries of the 'Output' subsection that belong to the run as a
   * whole: where files go, the summary file and checkpoints. Each
   * postprocessor (postprocess/interface.h) declares its own entries in
   * the same subsection.
   */
  struct OutputParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);

    void
    parse_parameters(ParameterHandler &prm);

    std::string  directory;
    std::string  summary_file;
    unsigned int summary_interval;
    /// 'Summary displacement unit' (length units).
    double       summary_displacement_unit = 1;
    unsigned int checkpoint_interval;
  };
} // namespace tissuefem::output
