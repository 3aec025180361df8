#pragma once

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>

namespace tissuefem
{
  /**
   * Reductions of errors and distances that keep a NaN. std::max(worst, x)
   * returns worst when x is NaN (every comparison with NaN is false), so a
   * NaN error would read as the errors before it, zero at first, and a
   * check would print "ok". These return NaN as soon as any value is NaN.
   */
  inline double
  max_keeping_nan(const double a, const double b)
  {
    if (std::isnan(a) || std::isnan(b))
      return std::numeric_limits<double>::quiet_NaN();
    return std::max(a, b);
  }

  inline double
  max_keeping_nan(const std::initializer_list<double> values)
  {
    double worst = -std::numeric_limits<double>::infinity();
    for (const double x : values)
      worst = max_keeping_nan(worst, x);
    return worst;
  }

  /// The largest of @p local over the processes of @p comm, NaN on every
  /// process if it is NaN on any (MPI_MAX leaves NaN to the implementation).
  inline double
  mpi_max_keeping_nan(const double local, const MPI_Comm comm)
  {
    const bool any_nan
      = dealii::Utilities::MPI::max(std::isnan(local) ? 1 : 0, comm) > 0;
    if (any_nan)
      return std::numeric_limits<double>::quiet_NaN();
    return dealii::Utilities::MPI::max(local, comm);
  }
} // namespace tissuefem
