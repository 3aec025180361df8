#pragma once

#include <tissuefem/base/input_error.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <string>

namespace tissuefem::output
{
  /// Creates @p path for the rows of a CSV file (10 significant digits);
  /// throws InputError naming 'Output/Directory' if it cannot.
  inline void
  create_file(std::ofstream &stream, const std::string &path)
  {
    stream.open(path);
    require(static_cast<bool>(stream),
            "Output/Directory",
            "cannot write '" + path + "'");
    stream << std::setprecision(10);
  }

  /// Reopens @p path to append rows (a restart).
  inline void
  append_to_file(std::ofstream &stream, const std::string &path)
  {
    stream.open(path, std::ios::out | std::ios::app);
    require(static_cast<bool>(stream),
            "Output/Directory",
            "cannot append to '" + path + "'");
    stream << std::setprecision(10);
  }

  /// Writes @p path whole through @p writer(std::ostream &): into a
  /// temporary file, then renamed, so no reader sees half a file.
  template <typename Writer>
  void
  write_whole(const std::string &path, const Writer &writer)
  {
    {
      std::ofstream file(path + ".tmp");
      writer(file);
    }
    std::filesystem::rename(path + ".tmp", path);
  }
} // namespace tissuefem::output
