#pragma once

#include <deal.II/base/exceptions.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/point.h>
#include <deal.II/base/types.h>

#include <tissuefem/base/parallel.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace tissuefem
{
  using namespace dealii;

  /// Splits @p text at @p separator and trims white space from each piece.
  std::vector<std::string>
  split_and_trim(const std::string &text, const char separator);

  /**
   * Splits a list of entries separated by a single '|'. A '||' (muparser's
   * logical or) is kept inside its entry.
   */
  std::vector<std::string>
  split_entries(const std::string &text);

  /// A boundary id 0..254 from @p text; InputError naming @p parameter
  /// otherwise.
  types::boundary_id
  parse_boundary_id(const std::string &text, const std::string &parameter);

  /**
   * Entries 'id: rest' separated by '|' (see split_entries()), as pairs of
   * the boundary id and the trimmed text after the first ':'.
   */
  std::vector<std::pair<types::boundary_id, std::string>>
  parse_id_entries(const std::string &text, const std::string &parameter);

  /// Whether an expression uses the variable @p name as a whole
  /// identifier ('t' is not inside 'sqrt' or 'atan').
  bool
  names_variable(const std::string &expression, const std::string &name);

  /// The muparser variable names for points in @p dim dimensions plus time.
  std::string
  expression_variables(const unsigned int dim);

  /**
   * A muparser function of (x, y, z, t) (as many space variables as @p dim)
   * with @p n_components components given as expressions separated by ';'.
   * A single expression is used for every component. Errors in the
   * expressions are reported as InputError naming @p parameter.
   */
  template <int dim>
  std::unique_ptr<FunctionParser<dim>>
  make_function(const std::string &expressions,
                const unsigned int n_components,
                const std::string &parameter);

  /// The comma-separated finite numbers of @p text; an InputError
  /// "@p what: 'item' is not a finite number" otherwise.
  std::vector<double>
  parse_numbers(const std::string &text, const std::string &what);

  /// A point from "x, y[, z]" with exactly @p dim coordinates.
  template <int dim>
  Point<dim>
  parse_point(const std::string &text, const std::string &parameter);

  /**
   * The first @p n pieces of @p text separated by @p separator, joined again
   * (all of them if there are fewer), so that 3D-shaped values and defaults
   * serve lower dimensions.
   */
  std::string
  leading_entries(const std::string &text,
                  const char         separator,
                  const unsigned int n);

  /// A point from the first @p dim of at least @p dim coordinates "x, y, z".
  template <int dim>
  Point<dim>
  parse_leading_point(const std::string &text, const std::string &parameter);

  /// Points separated by ';', each parsed by parse_point().
  template <int dim>
  std::vector<Point<dim>>
  parse_points(const std::string &text, const std::string &parameter);

  /// The message of a deal.II exception, without its source location, on
  /// one line.
  std::string
  one_line_message(const ExceptionBase &exception);

  /// Whether every entry of @p v is finite. (deal.II's Vector::l2_norm()
  /// asserts finiteness in Debug mode, so it cannot serve as the check.)
  template <typename Vector>
  bool
  all_finite(const Vector &v)
  {
    for (const auto x : v)
      if (!std::isfinite(x))
        return false;
    return true;
  }

  /// For a distributed vector: whether every entry on every process is
  /// finite. Collective, so that all processes take the same branch.
  inline bool
  all_finite(const TrilinosWrappers::MPI::Vector &v)
  {
    bool local = true;
    for (const auto x : v)
      if (!std::isfinite(x))
        {
          local = false;
          break;
        }
    return Utilities::MPI::min(local ? 1 : 0, v.get_mpi_communicator()) == 1;
  }

  /// The l2 norm of @p v, or NaN if any entry is not finite (collective for
  /// distributed vectors).
  template <typename Vector>
  double
  checked_l2_norm(const Vector &v)
  {
    return all_finite(v) ? double(v.l2_norm())
                         : std::numeric_limits<double>::quiet_NaN();
  }

  /// Collapses new lines and runs of white space into single spaces.
  std::string
  squeeze_whitespace(const std::string &text);
} // namespace tissuefem
