#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/output/summary_file.h>

namespace tissuefem::output
{
  SummaryFile::SummaryFile(const std::string &path,
                           const unsigned int interval,
                           const double       displacement_unit)
      : file_path(path)
      , interval(interval)
      , unit(displacement_unit)
  {
  }


  std::string
  SummaryFile::unit_label() const
  {
    if (unit == 1)
      return {};
    std::ostringstream label;
    label << " / " << unit;
    return label.str();
  }


  void
  SummaryFile::open()
  {
    if (file_path.empty() || !parallel_tools::is_root())
      return;
    stream.open(file_path);
    require(static_cast<bool>(stream),
            "Output/Summary file",
            "cannot write '" + file_path + "'");
  }


  void
  SummaryFile::resume()
  {
    if (file_path.empty() || !parallel_tools::is_root())
      return;
    stream.open(file_path, std::ios::out | std::ios::app);
  }


  bool
  SummaryFile::active() const
  {
    return stream.is_open();
  }


  bool
  SummaryFile::due(const unsigned int step) const
  {
    return active() && step % interval == 0;
  }


  void
  SummaryFile::line(const std::string &text)
  {
    if (stream.is_open())
      stream << text << '\n' << std::flush;
  }


  const std::string &
  SummaryFile::path() const
  {
    return file_path;
  }


  void
  SummaryFile::flush()
  {
    if (stream.is_open())
      stream.flush();
  }
} // namespace tissuefem::output
