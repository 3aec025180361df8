#pragma once

#include <deal.II/base/parameter_handler.h>

#include <tissuefem/study/report.h>

#include <optional>
#include <string>
#include <vector>

namespace tissuefem::study
{
  using namespace dealii;

  /**
   * The 'Study/Model choice' subsection: model no more than a scene needs.
   * Given an error tolerance in the study's quantity and a wall-clock
   * budget per step (the frame of a real-time loop), the picker takes, of
   * the variants that meet both, the one that costs least per simulated
   * time, and runs the scene with it.
   */
  struct PickerParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /// Largest acceptable errors, one choice each (0: do not pick).
    std::vector<double> tolerances;
    /// Wall-clock budgets per step (s), one choice each; 0: no budget.
    std::vector<double> budgets;
    bool                run_choice;
  };

  struct Choice
  {
    /// Index into the rows, if any variant meets both demands.
    std::optional<unsigned int> row;
    /// Why: the decisive rows, in words.
    std::string explanation;
  };

  /**
   * Picks among @p rows: a variant qualifies if it finished, its error is
   * at most the tolerance and it runs in real time at frames of @p budget
   * (0: any): its mean step is at most a frame, and the steps of a frame
   * (ceil(budget / step)) at its 95th-percentile step wall time take at
   * most the frame's duration. Of those, the least wall time of the steps per
   * simulated time unit wins. The explanation names the winner and every
   * cheaper variant with the demand it missed.
   */
  Choice
  pick(const std::vector<Row> &rows,
       const double            tolerance,
       const double            budget,
       const std::string      &quantity);
} // namespace tissuefem::study
