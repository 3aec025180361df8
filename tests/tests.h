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
#include <utility>
#include <vector>

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

  class EachModel;

  /// The EachModel gathering checks now, if any.
  inline EachModel *&
  gathering()
  {
    static EachModel *active = nullptr;
    return active;
  }

  inline void
  check(const bool         condition,
        const std::string &name,
        const std::string &detail = "");

  /**
   * Checks repeated over every registered model, printed as one line per
   * kind of check instead of one per model, so that the stored output
   * does not change when a model is registered. While an EachModel lives,
   * a check named "<prefix> <model><rest>" (model: the last one given to
   * model()) is gathered under "<prefix> <label><rest>"; the destructor
   * prints each such line once, in the order first seen, "ok" if every
   * model passed, else FAILED naming the models and their details.
   */
  class EachModel
  {
  public:
    EachModel(const std::string &prefix,
              const std::string &label = "each registered model")
        : prefix(prefix)
        , label(label)
    {
      gathering() = this;
    }

    ~EachModel()
    {
      gathering() = nullptr;
      for (const auto &[name, failed] : results)
        check(failed.empty(), name, failed);
    }

    /// The model the next checks are about.
    void
    model(const std::string &name)
    {
      current = name;
    }

    void
    record(const bool         condition,
           const std::string &name,
           const std::string &detail)
    {
      const std::string head = prefix + " " + current;
      const std::string key
        = name.compare(0, head.size(), head) == 0
            ? prefix + " " + label + name.substr(head.size())
            : name;
      auto found = results.begin();
      while (found != results.end() && found->first != key)
        ++found;
      if (found == results.end())
        {
          results.emplace_back(key, "");
          found = results.end() - 1;
        }
      if (!condition)
        found->second += "[" + current + ": " + detail + "] ";
    }

  private:
    std::string prefix, label, current;
    /// (gathered name, failures so far) in the order first seen.
    std::vector<std::pair<std::string, std::string>> results;
  };

  /// Prints "name: ok" if @p condition holds, else a failure line with
  /// @p detail, and counts the failure; inside an EachModel, gathers it.
  inline void
  check(const bool         condition,
        const std::string &name,
        const std::string &detail)
  {
    if (EachModel *each = gathering())
      {
        each->record(condition, name, detail);
        return;
      }
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
