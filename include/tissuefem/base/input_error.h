#pragma once

#include <stdexcept>
#include <string>

namespace tissuefem
{
  /**
   * An error in what the user gave us (a parameter value, a file, an
   * expression). Its message is one line and names the parameter or file.
   * The executable prints it and exits with a non-zero status before any
   * output file is written.
   */
  class InputError : public std::runtime_error
  {
  public:
    explicit InputError(const std::string &message)
        : std::runtime_error(message)
    {
    }
  };

  /**
   * A failure of the computation itself (Newton did not converge after all
   * permitted step reductions, an element inverted in a model that cannot
   * represent inversion, ...).
   */
  class SolverError : public std::runtime_error
  {
  public:
    explicit SolverError(const std::string &message)
        : std::runtime_error(message)
    {
    }
  };

  /// Throws InputError "Parameter 'name': message" unless @p condition holds.
  inline void
  require(const bool         condition,
          const std::string &parameter,
          const std::string &message)
  {
    if (!condition)
      throw InputError("Parameter '" + parameter + "': " + message);
  }
} // namespace tissuefem
