#pragma once

#include <deal.II/base/tensor.h>

#include <array>
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
   * The grasping tool follows one; so may a contact obstacle, whose rows
   * may also carry its rotation (poses: a few more columns after the
   * coordinates, interpolated alike).
   */
  template <int dim>
  class TrajectoryTable
  {
  public:
    /// Reads @p file; errors name @p parameter, the file and the line.
    /// With @p rotations > 0, rows may carry that many more values (the
    /// same number on every row).
    static TrajectoryTable
    read(const std::string &file,
         const std::string &parameter,
         const unsigned int rotations = 0);

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

    /// Whether the rows carry rotations.
    bool
    has_rotation() const
    {
      return !angles.empty();
    }

    /// The rotation's values at @p time, interpolated as the positions
    /// (zero where the rows carry none).
    std::array<double, 3>
    rotation(const double time) const;

    /// The first row's position (0 if there are no rows).
    Tensor<1, dim>
    first() const
    {
      return empty() ? Tensor<1, dim>() : positions.front();
    }

  private:
    std::vector<double>         times;
    std::vector<Tensor<1, dim>> positions;
    /// Per row, its rotation's values (empty: the rows carry none).
    std::vector<std::array<double, 3>> angles;

    /// The rows around @p time and the weight of the later one.
    void
    locate(const double time, std::size_t &a, std::size_t &b, double &s) const;
  };
} // namespace tissuefem
