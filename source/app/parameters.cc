// Every parameter tissuefem knows, and reading a scene file into them.

#include <tissuefem/adaptation/mesh_adaptation.h>
#include <tissuefem/app/parameters.h>
#include <tissuefem/base/input_error.h>
#include <tissuefem/base/moved_entries.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/boundary/boundary_conditions.h>
#include <tissuefem/contact/obstacle.h>
#include <tissuefem/geometry/geometry.h>
#include <tissuefem/materials/consistency_check.h>
#include <tissuefem/materials/material_set.h>
#include <tissuefem/output/output_parameters.h>
#include <tissuefem/problems/interface.h>
#include <tissuefem/solid/discretization.h>
#include <tissuefem/solid/formulations/interface.h>
#include <tissuefem/solvers/linear_solver.h>
#include <tissuefem/solvers/newton.h>
#include <tissuefem/time/interface.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace tissuefem
{
  void
  declare_all_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Dimension",
                      "2",
                      Patterns::Integer(1, 3),
                      "Space dimension of the problem: 1, 2 or 3.");
    prm.declare_entry(
      "Problem",
      "elasticity",
      Patterns::Selection(
        problems::ProblemRegistry::instance().selection_pattern()),
      "What to compute. "
        + problems::ProblemRegistry::instance().documentation());
    geometry::GeometryParameters::declare_parameters(prm);
    solid::FiniteElementParameters::declare_parameters(prm);
    materials::MaterialParameters::declare_parameters(prm);
    solid::formulations::declare_parameters(prm);
    boundary::BoundaryParameters::declare_parameters(prm);
    time::TimeParameters::declare_parameters(prm);
    solvers::NewtonParameters::declare_parameters(prm);
    solvers::LinearSolver::declare_parameters(prm);
    output::OutputParameters::declare_parameters(prm);
    adaptation::MeshRefinementParameters::declare_parameters(prm);
    problems::ProblemRegistry::instance().declare_parameters(prm);
  }


  namespace
  {
    /**
     * Raises the 'Contact/Obstacle k' slots to those named by the
     * 'subsection Obstacle k' lines of @p file (comments stripped as
     * ParameterHandler strips them) and of the files it includes (as
     * read_parameters() finds them: relative to the directory of the file
     * it reads, @p top), and by the paths of @p overrides. An unreadable
     * file is left to read_parameters() to report.
     */
    void
    name_obstacle_slots(const std::string              &file,
                        const std::vector<std::string> &overrides,
                        std::filesystem::path           top   = {},
                        const unsigned int              depth = 0)
    {
      static const std::regex subsection(
        R"(^\s*subsection\s+Obstacle\s+([0-9]+)\s*$)");
      static const std::regex include(R"(^\s*include\s+(.*\S)\s*$)");
      static const std::regex path(R"((^|/)\s*Obstacle\s+([0-9]+)\s*(/|$))");
      if (depth == 0)
        top = std::filesystem::absolute(file).parent_path();
      std::ifstream in(file);
      std::string   line;
      std::smatch   match;
      while (in && std::getline(in, line))
        {
          for (std::size_t i = line.find('#'); i != std::string::npos;
               i             = line.find('#', i + 1))
            if (i == 0 || line[i - 1] != '\\')
              {
                            line.erase(i);
                            break;
              }
          if (std::regex_match(line, match, subsection))
            contact::name_obstacle_slot(match[1],
                                        "Parameter file '" + file + "'");
          else if (depth < 8 && std::regex_match(line, match, include))
            {
              std::filesystem::path included(match[1].str());
              if (included.is_relative())
                included = top / included;
              name_obstacle_slots(included.string(), {}, top, depth + 1);
            }
        }
      for (const std::string &assignment : overrides)
        {
          const std::string key = assignment.substr(0, assignment.find('='));
          if (std::regex_search(key, match, path))
            contact::name_obstacle_slot(match[2], "--set '" + assignment + "'");
        }
    }
  } // namespace


  void
  declare_parameters_for(ParameterHandler               &prm,
                         const std::string              &file,
                         const std::vector<std::string> &overrides)
  {
    name_obstacle_slots(file, overrides);
    declare_all_parameters(prm);
  }


  void
  read_parameters(ParameterHandler               &prm,
                  const std::string              &file,
                  const std::vector<std::string> &overrides)
  {
    if (!std::filesystem::is_regular_file(file))
      throw InputError("Parameter file '" + file + "' cannot be opened");
    try
      {
        // ParameterHandler opens 'include' files relative to the working
        // directory; a file's includes should not depend on where it is
        // run from, so they are read relative to its own directory (as
        // its mesh files are).
        const auto                  absolute = std::filesystem::absolute(file);
        const std::filesystem::path previous = std::filesystem::current_path();
        std::filesystem::current_path(absolute.parent_path());
        try
          {
            prm.parse_input(absolute.string());
          }
        catch (...)
          {
            std::filesystem::current_path(previous);
            throw;
          }
        std::filesystem::current_path(previous);
      }
    catch (const ExceptionBase &e)
      {
        throw InputError("Parameter file '" + file
                         + "': " + one_line_message(e));
      }

    // Values given at the old place of a moved entry go to the new one
    // before the overrides, so that an override wins at either place.
    moved_entries::apply(prm);
    for (const std::string &assignment : overrides)
      {
        const auto equals = assignment.find('=');
        if (equals == std::string::npos)
          throw InputError("--set '" + assignment
                           + "': expected 'Subsection/Name=value'");
        const std::string value
          = Utilities::trim(assignment.substr(equals + 1));
        try
          {
            moved_entries::set(prm, assignment.substr(0, equals), value);
          }
        catch (const ExceptionBase &e)
          {
            throw InputError("--set '" + assignment
                             + "': " + one_line_message(e));
          }
      }
  }
} // namespace tissuefem
