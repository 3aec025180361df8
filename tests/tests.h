// A small header for tissuefem's unit tests: a portable random source and
// checks that print one deterministic line each ("name: ok" or
// "name: FAILED ..."), so the stored .output file records which checks ran
// and the exit status records whether they passed.
#pragma once

#include <deal.II/base/tensor.h>

#include <tissuefem/base/nan_aware.h>

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <limits>
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

  /**
   * Raises @p worst to @p x, NaN if either is NaN: std::max(worst, x)
   * returns worst when x is NaN, so a NaN error would read as zero and its
   * check print "ok". With the environment variable
   * TISSUEFEM_TESTS_FEED_NAN set, the first value a program passes here is
   * replaced by NaN: ctest's "<test>.nan" runs do so and must fail, which
   * shows that each test's checks see a NaN.
   */
  inline void
  raise(double &worst, double x)
  {
    static bool fed = false;
    if (!fed && std::getenv("TISSUEFEM_TESTS_FEED_NAN") != nullptr)
      {
        fed = true;
        x   = std::numeric_limits<double>::quiet_NaN();
      }
    worst = tissuefem::max_keeping_nan(worst, x);
  }

  /// Lowers @p least to @p x, NaN if either is NaN (as raise()).
  inline void
  lower(double &least, const double x)
  {
    double negated = -least;
    raise(negated, -x);
    least = -negated;
  }

  /**
   * While it lives, std::cout writes on the first MPI process only: for
   * tests whose figures are global (sums over processes), so that one
   * process writes the output.
   */
  class OneWriter
  {
  public:
    OneWriter()
        : screen(std::cout.rdbuf())
    {
      int rank = 0;
      MPI_Comm_rank(MPI_COMM_WORLD, &rank);
      if (rank > 0)
        std::cout.rdbuf(muted.rdbuf());
    }

    ~OneWriter()
    {
      std::cout.rdbuf(screen);
    }

  private:
    std::ostringstream muted;
    std::streambuf    *screen;
  };

  /// While it lives, std::cout is discarded (a run's progress lines).
  class Muted
  {
  public:
    Muted()
        : screen(std::cout.rdbuf(muted.rdbuf()))
    {
    }

    ~Muted()
    {
      std::cout.rdbuf(screen);
    }

  private:
    std::ostringstream muted;
    std::streambuf    *screen;
  };

  /// The exit status: non-zero if any check failed.
  inline int
  exit_status()
  {
    return failures() == 0 ? 0 : 1;
  }
} // namespace tissuefem_tests
