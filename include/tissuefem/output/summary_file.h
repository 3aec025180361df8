#pragma once

#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>

namespace tissuefem::output
{
  /// "t = TIME LABEL = v_0 v_1 ..." with 8 significant digits: the summary
  /// line of a vector quantity (@p n components of @p values).
  template <typename Values>
  std::string
  vector_line(const double       time,
              const std::string &label,
              const Values      &values,
              const unsigned int n)
  {
    std::ostringstream line;
    line << std::setprecision(8) << "t = " << time << ' ' << label << " =";
    for (unsigned int c = 0; c < n; ++c)
      line << ' ' << values[c];
    return line.str();
  }

  /**
   * The optional 'Output/Summary file': lines of results without timings or
   * iteration counts, for regression tests. The run writes its header and
   * postprocessors their lines; only process 0 writes, and each line is
   * flushed whole, so an interrupted run leaves no partial line.
   */
  class SummaryFile
  {
  public:
    /// @p path empty: no summary file (every call does nothing);
    /// @p interval: steps between the per-step lines (due()).
    /// @p displacement_unit: 'Output/Summary displacement unit'.
    SummaryFile(const std::string &path,
                const unsigned int interval,
                const double       displacement_unit = 1);

    /// Creates the file (before any other output file: if it cannot be
    /// written, nothing is created). Process 0 only; throws InputError
    /// naming 'Output/Summary file'.
    void
    open();

    /// Reopens the file for appending (a restart; its length has been cut
    /// back to the checkpoint's).
    void
    resume();

    /// Whether there is a summary file on this process.
    bool
    active() const;

    /// Whether step @p step gets per-step lines ('Summary interval').
    bool
    due(const unsigned int step) const;

    /// Appends @p line (no trailing newline) and flushes.
    void
    line(const std::string &text);

    /// The file's path (empty if none).
    const std::string &
    path() const;

    /// The length unit of displacements in the file (length units), and
    /// the label suffix that names it (" / 0.0001"; empty for 1).
    double
    displacement_unit() const
    {
      return unit;
    }

    std::string
    unit_label() const;

    /// Flushes what was written (before a checkpoint measures the file).
    void
    flush();

  private:
    std::string   file_path;
    unsigned int  interval;
    double        unit;
    std::ofstream stream;
  };
} // namespace tissuefem::output
