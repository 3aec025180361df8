#pragma once

#include <chrono>

namespace tissuefem
{
  /// Wall-clock seconds since @p start (steady clock).
  inline double
  seconds_since(const std::chrono::steady_clock::time_point start)
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now()
                                         - start)
      .count();
  }
} // namespace tissuefem
