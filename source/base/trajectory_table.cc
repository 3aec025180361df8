#include <deal.II/base/utilities.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/base/trajectory_table.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>

namespace tissuefem
{


  template <int dim>
  TrajectoryTable<dim>
  TrajectoryTable<dim>::read(const std::string &file,
                             const std::string &parameter)
  {
    std::ifstream in(file);
    require(static_cast<bool>(in), parameter, "cannot open '" + file + "'");
    TrajectoryTable table;
    std::string     line;
    for (unsigned int number = 1; std::getline(in, line); ++number)
      {
        // A UTF-8 byte order mark (spreadsheet exports) is no data.
        if (number == 1 && line.compare(0, 3, "\xEF\xBB\xBF") == 0)
          line.erase(0, 3);
        if (Utilities::trim(line).empty())
          continue;
        const std::string where
          = "File '" + file + "', line " + std::to_string(number) + ": ";
        std::vector<double> row;
        try
          {
            row = parse_numbers(line, "");
          }
        catch (const InputError &)
          {
            // A first line with a letter in it is a header; a typo in a
            // first row of numbers is not.
            if (number == 1
                && std::any_of(line.begin(), line.end(), [](const char c) {
                     return std::isalpha(static_cast<unsigned char>(c));
                   }))
              continue;
            throw InputError(where + "not a row of finite numbers");
          }
        if (row.size() != dim + 1)
          throw InputError(where + "expected " + std::to_string(dim + 1)
                           + " values (t and the coordinates), got "
                           + std::to_string(row.size()));
        if (!table.empty() && !(row[0] > table.times.back()))
          throw InputError(where + "times must increase");
        Tensor<1, dim> position;
        for (unsigned int d = 0; d < dim; ++d)
          position[d] = row[d + 1];
        table.append(row[0], position);
      }
    require(!table.empty(), parameter, "'" + file + "' holds no positions");
    return table;
  }


  template <int dim>
  void
  TrajectoryTable<dim>::append(const double          time,
                               const Tensor<1, dim> &position)
  {
    if (!times.empty() && !(time > times.back()))
      return;
    times.push_back(time);
    positions.push_back(position);
  }


  template <int dim>
  double
  TrajectoryTable<dim>::last_time() const
  {
    return times.empty() ? -std::numeric_limits<double>::infinity()
                         : times.back();
  }


  template <int dim>
  Tensor<1, dim>
  TrajectoryTable<dim>::position(const double time) const
  {
    if (times.empty())
      return {};
    const auto after = std::upper_bound(times.begin(), times.end(), time);
    if (after == times.begin())
      return positions.front();
    if (after == times.end())
      return positions.back();
    const std::size_t b = after - times.begin(), a = b - 1;
    const double      s = (time - times[a]) / (times[b] - times[a]);
    return (1 - s) * positions[a] + s * positions[b];
  }


  template class TrajectoryTable<1>;
  template class TrajectoryTable<2>;
  template class TrajectoryTable<3>;
} // namespace tissuefem
