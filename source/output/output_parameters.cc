#include <tissuefem/base/input_error.h>
#include <tissuefem/output/output_parameters.h>

namespace tissuefem::output
{
  void
  OutputParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.declare_entry("Directory",
                      "output",
                      Patterns::Anything(),
                      "Directory (relative to the working directory) that "
                      "receives solution-*.pvtu/.vtu, solution.pvd, "
                      "statistics.csv, probes.csv and reactions.csv; created "
                      "if missing.");
    prm.declare_entry("Summary file",
                      "",
                      Patterns::Anything(),
                      "If not empty: a file (relative to the working "
                      "directory) receiving the probe displacements, "
                      "reaction forces and final elastic energy (and the "
                      "rest-shape report) without timings or iteration "
                      "counts, for regression tests. Its directory must "
                      "exist.");
    prm.declare_entry("Summary interval",
                      "1",
                      Patterns::Integer(1),
                      "Steps between rows of the summary file.");
    prm.declare_entry(
      "Summary displacement unit",
      "1",
      Patterns::Double(1e-300),
      "Length units (> 0) in which the summary file prints probe "
      "displacements ('probe 0 u / 0.0001 = ...' for 1e-4). Regression "
      "tests compare with numdiff, which takes values below 1e-6 as equal: "
      "a scene whose displacements are of order 1e-5 states them in a "
      "unit that brings them to order 1, so that their digits are "
      "compared. Other outputs are unaffected.");
    prm.declare_entry(
      "Checkpoint interval",
      "0",
      Patterns::Integer(0),
      "Steps between checkpoints written to '<Directory>/checkpoint' "
      "(atomically: a new one replaces the old one whole); 0: only when the "
      "run is interrupted by SIGINT or SIGTERM. 'tissuefem FILE.prm "
      "--restart <Directory>/checkpoint' continues the run; its outputs are "
      "then those of an uninterrupted run, bit for bit except the "
      "wall-clock columns of statistics.csv (same FILE.prm and "
      "process count; quasistatic, backward Euler, and damped central "
      "difference without active region; no tool but the live view's "
      "mouse, which is checkpointed only while it holds nothing; no mesh "
      "adaptation).");
    prm.leave_subsection();
  }


  void
  OutputParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    directory                 = prm.get("Directory");
    summary_file              = prm.get("Summary file");
    summary_interval          = prm.get_integer("Summary interval");
    summary_displacement_unit = prm.get_double("Summary displacement unit");
    checkpoint_interval       = prm.get_integer("Checkpoint interval");
    prm.leave_subsection();
    require(!directory.empty(), "Output/Directory", "must not be empty");
  }
} // namespace tissuefem::output
