#pragma once

#include <map>
#include <string>
#include <vector>

namespace tissuefem::output
{
  /**
   * The figures of one finished run in '<Output/Directory>/run.txt', one
   * 'key = value  # unit or definition' line each: what a study reads back
   * (mesh size, wall times, memory, errors, quantities of interest). Written
   * at the end of a run through a temporary name, so the file exists only
   * for runs that finished.
   */
  class RunRecord
  {
  public:
    /// Appends @p key (without '=' or '#') with its unit or definition.
    void
    add(const std::string &key, const double value, const std::string &unit);

    /// Writes the record to @p file (process 0 only).
    void
    write(const std::string &file) const;

    /// Reads a record; throws InputError naming @p file if it is missing or
    /// malformed.
    static std::map<std::string, double>
    read(const std::string &file);

  private:
    struct Entry
    {
      std::string key;
      double      value;
      std::string unit;
    };
    std::vector<Entry> entries;
  };
} // namespace tissuefem::output
