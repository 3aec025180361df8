#include <deal.II/base/utilities.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/output/run_record.h>

#include <cstdio>
#include <fstream>
#include <iomanip>
#include <limits>

namespace tissuefem::output
{
  void
  RunRecord::add(const std::string &key,
                 const double       value,
                 const std::string &unit)
  {
    entries.push_back({key, value, unit});
  }


  void
  RunRecord::write(const std::string &file) const
  {
    const std::string temporary = file + ".new";
    {
      std::ofstream out(temporary);
      require(static_cast<bool>(out),
              "Output/Directory",
              "cannot write '" + file + "'");
      out << std::setprecision(std::numeric_limits<double>::max_digits10);
      for (const auto &e : entries)
        out << e.key << " = " << e.value << "  # " << e.unit << '\n';
      out.close();
      require(static_cast<bool>(out),
              "Output/Directory",
              "cannot write '" + file + "'");
    }
    require(std::rename(temporary.c_str(), file.c_str()) == 0,
            "Output/Directory",
            "cannot rename '" + temporary + "' to '" + file + "'");
  }


  std::map<std::string, double>
  RunRecord::read(const std::string &file)
  {
    std::ifstream in(file);
    if (!in)
      throw InputError("run record '" + file + "' cannot be read");
    std::map<std::string, double> values;
    std::string                   line;
    while (std::getline(in, line))
      {
        const auto equals = line.find('=');
        const auto hash   = line.find('#');
        if (line.empty())
          continue;
        if (equals == std::string::npos || hash < equals)
          throw InputError("run record '" + file + "': malformed line '" + line
                           + "'");
        const std::string key = dealii::Utilities::trim(line.substr(0, equals));
        const std::string value = dealii::Utilities::trim(
          line.substr(equals + 1,
                      hash == std::string::npos ? std::string::npos
                                                : hash - equals - 1));
        try
          {
            std::size_t used = 0;
            values[key]      = std::stod(value, &used);
            if (used != value.size())
              throw std::invalid_argument(value);
          }
        catch (const std::exception &)
          {
            // 'inf' and 'nan' are read by stod; anything else is an error.
            throw InputError("run record '" + file + "': value of '" + key
                             + "' is not a number");
          }
      }
    return values;
  }
} // namespace tissuefem::output
