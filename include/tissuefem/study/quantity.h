#pragma once

#include <deal.II/base/parameter_handler.h>

#include <map>
#include <string>
#include <vector>

namespace tissuefem::study
{
  using namespace dealii;

  /**
   * The 'Study/Quantity' entries: what a study measures the error of, and
   * against what. Errors against the manufactured solution come from the
   * runs themselves (run.txt); the others compare a run's outputs with a
   * closed-form value or with a reference run (the scene run with
   * 'Reference settings', finer in space and time than every variant).
   */
  struct QuantityParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /// 'L2 error', 'H1 error', ... (manufactured), 'probe final',
    /// 'probe history' or 'stored energy'.
    std::string  quantity;
    unsigned int probe;
    /// Displacement component of probe quantities (-1: all, Euclidean).
    int component;
    /// 'manufactured', 'value' or 'reference run'.
    std::string         reference;
    std::vector<double> reference_value;
    std::string         reference_settings;
    bool                relative;

    /// The quantity's name with its unit or definition, for tables.
    std::string
    describe() const;
  };

  /// Probe displacements of one run: time -> components, for one probe.
  using ProbeHistory = std::map<double, std::vector<double>>;

  /// Reads probe @p probe from '<dir>/probes.csv' (only displacement
  /// component @p component if >= 0); throws InputError if the file is
  /// missing or malformed.
  ProbeHistory
  read_probe_history(const std::string &directory,
                     const unsigned int probe,
                     const int          component = -1);

  /**
   * The error of the run in @p directory (with its run record @p record)
   * in the quantity of @p parameters; @p reference_directory is the
   * reference run's (empty unless 'reference run').
   */
  double
  quantity_error(const QuantityParameters            &parameters,
                 const std::string                   &directory,
                 const std::map<std::string, double> &record,
                 const std::string                   &reference_directory);
} // namespace tissuefem::study
