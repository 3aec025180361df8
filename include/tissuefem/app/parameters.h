#pragma once

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <utility>
#include <vector>

namespace tissuefem
{
  using namespace dealii;

  /// Declares every parameter tissuefem knows, with its documentation.
  void
  declare_all_parameters(ParameterHandler &prm);

  /**
   * declare_all_parameters() with as many 'Contact/Obstacle k' slots as
   * @p file, the files it includes and @p overrides name (a scene may have
   * any number of obstacles, up to contact::largest_obstacle_slot).
   */
  void
  declare_parameters_for(ParameterHandler               &prm,
                         const std::string              &file,
                         const std::vector<std::string> &overrides);

  /**
   * Reads @p file into @p prm, then applies @p overrides, each
   * "Subsection/Name=value". Throws InputError naming the file or parameter
   * on any problem.
   */
  void
  read_parameters(ParameterHandler               &prm,
                  const std::string              &file,
                  const std::vector<std::string> &overrides);
} // namespace tissuefem
