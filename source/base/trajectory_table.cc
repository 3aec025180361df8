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
                             const std::string &parameter,
                             const unsigned int rotations)
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
        // The first row says whether the rows carry rotations.
        const bool        first = table.empty();
        const std::size_t plain = dim + 1, posed = dim + 1 + rotations;
        const bool        fits
          = first
              ? row.size() == plain || (rotations > 0 && row.size() == posed)
              : row.size() == (table.has_rotation() ? posed : plain);
        if (!fits)
          {
            std::string expected
              = first || !table.has_rotation()
                  ? std::to_string(plain) + " values (t and the coordinates)"
                  : std::to_string(posed)
                      + " values (t, the coordinates and the rotation, as on "
                        "the first row)";
            if (first && rotations > 0)
              expected += " or " + std::to_string(posed)
                          + " (t, the coordinates and the rotation)";
            throw InputError(where + "expected " + expected + ", got "
                             + std::to_string(row.size()));
          }
        if (!table.empty() && !(row[0] > table.times.back()))
          throw InputError(where + "times must increase");
        Tensor<1, dim> position;
        for (unsigned int d = 0; d < dim; ++d)
          position[d] = row[d + 1];
        table.append(row[0], position);
        if (row.size() > dim + 1)
          {
            std::array<double, 3> angle{{0, 0, 0}};
            for (unsigned int r = 0; r < rotations; ++r)
              angle[r] = row[dim + 1 + r];
            if (table.angles.size() == table.times.size())
              table.angles.back() = angle;
            else
              table.angles.push_back(angle);
          }
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
    // A row appended to rows with rotations keeps the last rotation.
    if (!angles.empty())
      angles.push_back(angles.back());
  }


  template <int dim>
  double
  TrajectoryTable<dim>::last_time() const
  {
    return times.empty() ? -std::numeric_limits<double>::infinity()
                         : times.back();
  }


  template <int dim>
  void
  TrajectoryTable<dim>::locate(const double time,
                               std::size_t &a,
                               std::size_t &b,
                               double      &s) const
  {
    const auto after = std::upper_bound(times.begin(), times.end(), time);
    s                = 0;
    if (after == times.begin())
      a = b = 0;
    else if (after == times.end())
      a = b = times.size() - 1;
    else
      {
        b = after - times.begin();
        a = b - 1;
        s = (time - times[a]) / (times[b] - times[a]);
      }
  }


  template <int dim>
  Tensor<1, dim>
  TrajectoryTable<dim>::position(const double time) const
  {
    if (times.empty())
      return {};
    std::size_t a, b;
    double      s;
    locate(time, a, b, s);
    return (1 - s) * positions[a] + s * positions[b];
  }


  template <int dim>
  std::array<double, 3>
  TrajectoryTable<dim>::rotation(const double time) const
  {
    std::array<double, 3> result{{0, 0, 0}};
    if (angles.empty())
      return result;
    std::size_t a, b;
    double      s;
    locate(time, a, b, s);
    for (unsigned int r = 0; r < 3; ++r)
      result[r] = (1 - s) * angles[a][r] + s * angles[b][r];
    return result;
  }


  template class TrajectoryTable<1>;
  template class TrajectoryTable<2>;
  template class TrajectoryTable<3>;
} // namespace tissuefem
