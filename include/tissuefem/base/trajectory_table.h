#pragma once

#include <deal.II/base/tensor.h>

#include <string>
#include <vector>

namespace tissuefem
{
  using namespace dealii;

  /**
   * Positions against time, recorded from a device or written by hand: rows
   * (t, x, y[, z]) with increasing times, interpolated linearly between
   * rows and held beyond the ends. Read from a CSV file (a first line that
   * is not numeric is a header) or appended row by row (a live client).
   * The grasping tool follows one; so may a contact obstacle.
   */
  template <int dim>
  class TrajectoryTable
  {
  public:
    /// Reads @p file; errors name @p parameter, the file and the line.
    static TrajectoryTable
    read(const std::string &file, const std::string &parameter);

    /// Appends a row later than the last (earlier ones are ignored).
    void
    append(const double time, const Tensor<1, dim> &position);

    bool
    empty() const
    {
      return times.empty();
    }

    /// The last row's time (-infinity if there is none).
    double
    last_time() const;

    /// The position at @p time (0 if there are no rows).
    Tensor<1, dim>
    position(const double time) const;

    /// The first row's position (0 if there are no rows).
    Tensor<1, dim>
    first() const
    {
      return empty() ? Tensor<1, dim>() : positions.front();
    }

  private:
    std::vector<double>         times;
    std::vector<Tensor<1, dim>> positions;
  };
} // namespace tissuefem
