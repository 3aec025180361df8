// A small header for tissuefem's unit tests: a portable random source and
// checks that print one deterministic line each ("name: ok" or
// "name: FAILED ..."), so the stored .output file records which checks ran
// and the exit status records whether they passed.
#pragma once

#include <deal.II/base/tensor.h>

#include <cmath>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>

namespace tissuefem_tests
{
  /// A 64-bit linear congruential generator: the same numbers on every
  /// platform and standard library.
  class Random
  {
  public:
    explicit Random(const std::uint64_t seed)
        : state(seed)
    {
    }

    /// Uniform in [-1, 1).
    double
    uniform()
    {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      return static_cast<double>(state >> 11) / 4503599627370496.0 - 1.0;
    }

  private:
    std::uint64_t state;
  };

  inline int &
  failures()
  {
    static int count = 0;
    return count;
  }

  /// Prints "name: ok" if @p condition holds, else a failure line with
  /// @p detail, and counts the failure.
  inline void
  check(const bool         condition,
        const std::string &name,
        const std::string &detail = "")
  {
    if (condition)
      std::cout << name << ": ok" << std::endl;
    else
      {
        std::cout << name << ": FAILED " << detail << std::endl;
        ++failures();
      }
  }

  /// Checks |value| <= tolerance, printing the value on failure only.
  inline void
  check_small(const double       value,
              const double       tolerance,
              const std::string &name)
  {
    std::ostringstream bound;
    bound << std::scientific << std::setprecision(0) << tolerance;
    check(std::abs(value) <= tolerance,
          name + " (below " + bound.str() + ")",
          "value " + std::to_string(value));
  }

  /// The exit status: non-zero if any check failed.
  inline int
  exit_status()
  {
    return failures() == 0 ? 0 : 1;
  }
} // namespace tissuefem_tests
