// Cook's membrane for unit tests: the scene of parameters/cook_membrane.prm
// (nearly incompressible neo-Hookean, nu = 0.4999, the mean dilatation
// element, quasistatic), and the run of its elasticity problem with the
// tip deflection it ends with.
#pragma once

#include <deal.II/base/parameter_handler.h>

#include <tissuefem/app/parameters.h>
#include <tissuefem/problems/interface.h>

#include <cctype>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

namespace tissuefem_tests
{
  using namespace dealii;
  using namespace tissuefem;

  /// The scene on @p subdivisions ("16, 16") cells, then @p extra.
  inline std::string
  cook_membrane(const std::string &subdivisions, const std::string &extra)
  {
    return R"(
    set Dimension = 2
    subsection Geometry
      set Corners      = 0, 0; 48, 44; 0, 44; 48, 60
      set Subdivisions = )"
           + subdivisions + R"(
    end
    subsection Materials
      set Model           = neo-Hookean
      set Formulation     = mean dilatation
      set Young's modulus = 240.5659612
      set Poisson's ratio = 0.4999
    end
    subsection Boundary conditions
      set Dirichlet = 0: xy: 0; 0
      set Neumann   = 1: 0; 6.25*t
    end
    subsection Time integration
      set Integrator = quasistatic
      set End time   = 1
    end
    )" + extra;
  }


  /// The scene adapting by the stress-jump indicator from 4 x 4 cells
  /// without coarsening, in load steps of 0.05, then @p extra (later
  /// entries override earlier ones).
  inline std::string
  adaptive_cook_membrane(const std::string &extra)
  {
    return cook_membrane("4, 4", R"(
    subsection Time integration
      set Time step = 0.05
    end
    subsection Mesh refinement
      set Indicator        = stress jump
      set Coarsen fraction = 0
    end
    )" + extra);
  }


  /// What an adaptive run of the scene ended with.
  struct CookRun
  {
    /// The failure message; empty if the run completed.
    std::string failure;
    /// Everything the run printed (iteration counts: not for comparing).
    std::string screen;
    /// The time and the tip's vertical displacement on the last line of
    /// probes.csv (probe 0 at (48, 60)).
    double time = 0, tip = 0;
  };


  /// Runs the elasticity problem of adaptive_cook_membrane() with @p
  /// extra, up to 6 levels and @p cells cells, writing into
  /// @p directory.
  inline CookRun
  run_adaptive_cook(const unsigned int cells,
                    const std::string &directory,
                    const std::string &extra)
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    std::filesystem::remove_all(directory);
    prm.parse_input_from_string(adaptive_cook_membrane(R"(
    set Problem = elasticity
    subsection Mesh refinement
      set Maximum levels = 6
      set Maximum cells  = )" + std::to_string(cells) + R"(
    end
    subsection Newton solver
      set Maximum iterations = 100
    end
    subsection Output
      set Directory = )" + directory + R"(
      subsection VTU
        set Interval = 0
      end
      subsection Probes
        set Points = 48, 60
      end
    end
    )" + extra));
    CookRun            run;
    std::ostringstream screen;
    std::streambuf    *saved = std::cout.rdbuf(screen.rdbuf());
    try
      {
        auto problem = problems::ProblemRegistry::instance().create(
          "elasticity", prm, problems::RunContext{".", ""});
        problem->setup();
        problem->run();
      }
    catch (const std::exception &e)
      {
        run.failure = e.what();
      }
    std::cout.rdbuf(saved);
    run.screen = screen.str();
    // The last line of probes.csv: time, probe, X, Y, u_x, u_y.
    std::ifstream probes(directory + "/probes.csv");
    std::string   line, last;
    while (std::getline(probes, line))
      if (!line.empty() && std::isdigit(line[0]))
        last = line;
    double             values[6] = {};
    std::istringstream fields(last);
    for (double &value : values)
      {
        fields >> value;
        fields.ignore(1);
      }
    run.time = values[0];
    run.tip  = values[5];
    return run;
  }
} // namespace tissuefem_tests
