#pragma once

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace tissuefem::output
{
  /// Appends @p value's bytes to a binary message of the live view (the
  /// machine's order: little-endian on the machines this runs on, which
  /// the page's typed arrays read).
  template <typename T>
  void
  put(std::string &bytes, const T value)
  {
    bytes.append(reinterpret_cast<const char *>(&value), sizeof(T));
  }

  /// Appends the bytes of every entry of @p values.
  template <typename T>
  void
  put_all(std::string &bytes, const std::vector<T> &values)
  {
    bytes.append(reinterpret_cast<const char *>(values.data()),
                 values.size() * sizeof(T));
  }

  /// A number for JSON ("null" for inf and nan, which JSON lacks).
  inline std::string
  json_number(const double x)
  {
    if (!std::isfinite(x))
      return "null";
    std::ostringstream s;
    s.precision(10);
    s << x;
    return s.str();
  }
} // namespace tissuefem::output
