#pragma once

#include <tissuefem/study/variants.h>

#include <algorithm>
#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace tissuefem::study
{
  /// One variant's results.
  struct Row
  {
    Variant variant;
    /// "finished" or why the run failed (then only wall time is known).
    std::string status;
    bool        finished = false;
    /// The run's own record (run.txt) and the study's measurements.
    std::map<std::string, double> record;
    /// Wall time of the whole child process as the study measured it (s).
    double wall_seconds = 0;
    /// The error in the study's quantity.
    double error = 0;

    double
    get(const std::string &key) const
    {
      const auto it = record.find(key);
      return it == record.end() ? 0. : it->second;
    }

    /// Wall time of the steps per simulated time unit: what the variant
    /// costs a user (s per time unit).
    double
    cost() const;

    /// The mean step: simulated time / steps (time units).
    double
    mean_step() const
    {
      return get("simulated time") / std::max(1., get("steps"));
    }
  };

  /// Indices (into @p rows) of the finished variants on the Pareto front
  /// of error against wall time: no other finished variant has both a
  /// smaller error and a smaller wall time. Sorted by wall time.
  std::vector<unsigned int>
  pareto_front(const std::vector<Row> &rows);

  /// Writes 'results.csv': one line per variant, with units in the header.
  void
  write_csv(const std::string       &file,
            const std::vector<Axis> &axes,
            const std::vector<Row>  &rows,
            const std::string       &quantity);

  /**
   * Writes deal.II ConvergenceTable text to @p out and 'rates.csv' in
   * @p directory: one table per series (variants that differ only in the
   * axis @p rate_axis), with the observed order of the error against the
   * unknowns (in h ~ N^(-1/dim)) or against the mean time step.
   */
  void
  write_convergence_tables(std::ostream            &out,
                           const std::string       &directory,
                           const std::vector<Axis> &axes,
                           const std::vector<Row>  &rows,
                           const unsigned int       rate_axis,
                           const std::string       &rates_against,
                           const unsigned int       dim);

  /**
   * Writes gnuplot data and 'charts.gp' into @p directory and, if gnuplot
   * is installed, runs it to draw 'error_vs_unknowns.png' and
   * 'error_vs_wall_time.png' (the work-precision chart, Pareto front
   * marked and labelled). Returns a sentence on what was drawn.
   */
  std::string
  draw_charts(const std::string       &directory,
              const std::string       &title,
              const std::vector<Axis> &axes,
              const std::vector<Row>  &rows,
              const unsigned int       rate_axis,
              const std::string       &quantity);

  /// The summary paragraph: the variants on the front and the cheapest one
  /// for each tolerance.
  std::string
  summary_paragraph(const std::vector<Row>    &rows,
                    const std::vector<double> &tolerances,
                    const std::string         &quantity);
} // namespace tissuefem::study
