// Hertz indentation (parameters/hertz_indentation.prm, run as the program
// runs it): a rigid sphere (R = 40 mm) pressed d = 25 um into a thick
// linear-elastic block (E = 10 kPa, nu = 0.3), frictionless, one quarter by
// symmetry, against Hertz's closed form for a half-space:
//   F = 4/3 E / (1 - nu^2) R^(1/2) d^(3/2),  a = (R d)^(1/2)
// (Johnson, Contact Mechanics, section 4.2). The contact radius measured is
// (4 A / pi)^(1/2), A the reference area whose face quadrature points carry
// a pressure.
//
// At the sizes a test affords, the discretization error is a few percent
// to tens of percent, and the tolerances below match it (measured
// 2026-11-27; parameters/studies/hertz.sh follows it to finer meshes,
// doc/studies.md):
// - Q1 refined adaptively from the scene's graded box with 8 cells per
//   direction (Kelly indicator, 15 % of the cells per re-solve, two load
//   steps and three re-solves at full depth, 3 levels; force +2.3 %,
//   radius -6 %): force within 4 %, radius within 10 %, and the force
//   error at most a fifth of the unrefined mesh's (+33 %);
// - P1 on the graded box with 16 cells per direction (20,480 tetrahedra;
//   force +28 %, radius -44 %): force within 40 %, radius within 50 %,
//   and the force error at most a third of that with 8 cells per
//   direction (+125 %).
// All with the augmented Lagrangian (gaps within 1e-3 d). Also run
// on two processes.

#include <deal.II/base/mpi.h>

#include <tissuefem/app/parameters.h>

#include "../run_program.h"
#include "../tests.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace dealii;
using namespace tissuefem_tests;

namespace
{
  struct Measured
  {
    bool   ran         = false;
    double force_error = 0, radius_error = 0;
  };

  /// Runs the shipped scene with @p overrides (screen output muted) and
  /// compares its last contact.csv row with Hertz's closed form.
  Measured
  run(const std::string              &name,
      const double                    end_time,
      const std::vector<std::string> &overrides)
  {
    const std::string        directory = "results-" + name;
    std::vector<std::string> arguments
      = {std::string(SOURCE_DIR) + "/../../parameters/hertz_indentation.prm",
         "--set",
         "Output/Directory=" + directory,
         "--set",
         "Contact/Gap tolerance=2.5e-8"};
    for (const auto &o : overrides)
      {
        arguments.push_back("--set");
        arguments.push_back(o);
      }
    const int status = run_program(arguments);

    Measured      result;
    std::ifstream in(directory + "/contact.csv");
    std::string   line, last;
    while (std::getline(in, line))
      if (!line.empty())
        last = line;
    // time, obstacle, FX, FY, FZ, penetration, area, min/max pressure
    std::vector<std::string> fields;
    std::istringstream       row(last);
    for (std::string f; std::getline(row, f, ',');)
      fields.push_back(f);
    if (status != 0 || fields.size() != 9
        || std::abs(std::stod(fields[0]) - end_time) > 1e-9)
      return result;
    const double E = 1e4, nu = 0.3, R = 0.04, d = 2.5e-5;
    const double F
      = 4. / 3 * E / (1 - nu * nu) * std::sqrt(R) * std::pow(d, 1.5);
    const double a = std::sqrt(R * d);
    // The scene is a quarter: four times its force and area.
    const double F_h    = -4 * std::stod(fields[4]);
    const double a_h    = std::sqrt(4 * std::stod(fields[6]) / M_PI);
    result.ran          = F_h > 0;
    result.force_error  = F_h / F - 1;
    result.radius_error = a_h / a - 1;
    return result;
  }

  /// The checks of one element: both runs reach full depth, the finer
  /// one's force and radius within @p force and @p radius (relative), and
  /// its force error at most 1 / @p factor of the coarser one's.
  void
  check_pair(const std::string &element,
             const Measured    &coarse,
             const Measured    &fine,
             const double       force,
             const double       radius,
             const int          factor,
             const std::string &refinement)
  {
    check(coarse.ran && fine.ran,
          element
            + ": both runs reach full depth with the force into the "
              "block",
          "");
    check_small(fine.force_error, force, element + ": force error");
    check_small(fine.radius_error, radius, element + ": contact radius error");
    check(std::abs(fine.force_error) <= std::abs(coarse.force_error) / factor,
          element + ": " + refinement + " cuts the force error at least "
            + std::to_string(factor) + " times",
          "from " + std::to_string(coarse.force_error) + " to "
            + std::to_string(fine.force_error));
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const OneWriter                  one_writer;

  const std::string coarse_q1 = "Geometry/Subdivisions=8, 8, 8";
  const Measured    unrefined = run("q1-unrefined", 1, {coarse_q1});
  const Measured    adaptive
    = run("q1-adaptive",
          2.5,
          {coarse_q1,
           "Time integration/Time step=0.5",
           "Time integration/End time=2.5",
           "Contact/Obstacle 1/Motion=0; 0; -2.5e-5*min(t, 1)",
           "Mesh refinement/Indicator=Kelly",
           "Mesh refinement/Refine fraction=0.15",
           "Mesh refinement/Coarsen fraction=0",
           "Mesh refinement/Maximum levels=3"});
  check_pair("Q1", unrefined, adaptive, 0.04, 0.1, 5, "adaptive refinement");

  const std::string simplex = "Geometry/Cell type=simplex";
  const Measured    p1_coarse
    = run("p1-coarse", 1, {"Geometry/Subdivisions=8, 8, 8", simplex});
  const Measured p1
    = run("p1", 1, {"Geometry/Subdivisions=16, 16, 16", simplex});
  check_pair("P1", p1_coarse, p1, 0.4, 0.5, 3, "halving every cell");
  return exit_status();
}
