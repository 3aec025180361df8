// The damped central difference through first contact with tissue at rest
// (parameters/muscle_palpation.prm run explicitly, as the program runs it):
// a rigid sphere moves into Jeffrey's muscle, which starts at rest. Its
// stored plus kinetic energy is round-off before the sphere arrives and
// grows a thousandfold and more in the ten steps where it touches, which
// the scheme's instability test once took for an unstable step (the run
// stopped with exit 3 at t = 0.0156 s). Checked over t in [0, 0.04] s (dt =
// 2e-5 s):
// - the run completes, and the sphere has pushed the tissue (a force on
//   the tool at the end);
// - energy balance, independent of the scheme: the work W(t) the sphere
//   has done on the tissue (minus the integral of the force on the tool
//   along the tool's motion, trapezoidal over the steps) goes into stored
//   and kinetic energy, the penalty's spring and damping. So the stored
//   plus kinetic energy may never exceed it: checked at every step within
//   1 % of the largest W (the trapezoid's error). An unstable step would
//   gain energy from nothing and break it.

#include <deal.II/base/mpi.h>

#include <tissuefem/app/parameters.h>

#include "../run_program.h"
#include "../tests.h"

#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace dealii;
using namespace tissuefem_tests;

namespace
{
  /// The columns of a CSV file by name, each a list of its values.
  std::map<std::string, std::vector<double>>
  read_csv(const std::string &name)
  {
    std::ifstream                              in(name);
    std::string                                line;
    std::vector<std::string>                   header;
    std::map<std::string, std::vector<double>> columns;
    if (!std::getline(in, line))
      return columns;
    std::istringstream head(line);
    for (std::string field; std::getline(head, field, ',');)
      header.push_back(field);
    while (std::getline(in, line))
      {
        std::istringstream row(line);
        unsigned int       k = 0;
        for (std::string field;
             std::getline(row, field, ',') && k < header.size();
             ++k)
          columns[header[k]].push_back(std::stod(field));
      }
    return columns;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const OneWriter                  one_writer;

  const std::string directory = "results-explicit-contact";
  const int         status    = tissuefem_tests::run_program(
    {std::string(SOURCE_DIR) + "/../../parameters/muscle_palpation.prm",
                "--set",
                "Output/Directory=" + directory,
                "--set",
                "Time integration/Integrator=damped central difference",
                "--set",
                "Time integration/Time step=2e-5",
                "--set",
                "Time integration/End time=0.04",
                "--set",
                "Output/VTU/Interval=0"});

  auto        tool       = read_csv(directory + "/tool_force.csv");
  auto        statistics = read_csv(directory + "/statistics.csv");
  const auto &t          = tool["time"];
  const bool  complete
    = status == 0 && !t.empty() && std::abs(t.back() - 0.04) < 1e-9;
  check(complete,
        "the explicit run passes first contact and completes",
        "exit status " + std::to_string(status));
  if (!complete)
    return exit_status();
  check(std::abs(tool["force_x"].back()) > 0,
        "the sphere pushes the tissue at the end",
        "");

  // W at each tool row: minus the force on the tool along its motion.
  const char              *axes[] = {"x", "y", "z"};
  std::map<double, double> work{{t[0], 0.}};
  double                   W = 0, largest = 0;
  for (std::size_t i = 1; i < t.size(); ++i)
    {
      for (const char *a : axes)
        {
          const auto &f = tool[std::string("force_") + a];
          const auto &x = tool[std::string("tool_") + a];
          W -= 0.5 * (f[i] + f[i - 1]) * (x[i] - x[i - 1]);
        }
      work[t[i]] = W;
      largest    = std::max(largest, std::abs(W));
    }
  // Stored plus kinetic energy against W at the same times.
  const auto &time     = statistics["time"];
  const auto &stored   = statistics["stored_energy"];
  const auto &kinetic  = statistics["kinetic_energy"];
  double      excess   = 0;
  unsigned    compared = 0;
  for (std::size_t i = 0; i < time.size(); ++i)
    if (const auto w = work.lower_bound(time[i] - 1e-9);
        w != work.end() && std::abs(w->first - time[i]) < 1e-9)
      {
        raise(excess, (stored[i] + kinetic[i] - w->second) / largest);
        ++compared;
      }
  check(compared + 10 > t.size(),
        "every step's energy is compared with the sphere's work",
        std::to_string(compared) + " of " + std::to_string(t.size()));
  check(largest > 0, "the sphere does work on the tissue", "");
  check(excess <= 1e-2,
        "stored plus kinetic energy never exceeds the sphere's work "
        "(relative to the largest work, within 1e-2)",
        "excess " + std::to_string(excess));
  return exit_status();
}
