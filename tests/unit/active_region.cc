// Jeffrey's node freezing (report section 3) in the damped central
// difference: a 1D bar of 40 linear elements (E = 1, nu = 0, rho = 1),
// clamped at both ends, released from a narrow Gaussian bump at its middle,
// u0 = 0.01 exp(-400 (x - 1/2)^2), run to t = 0.15 with dt = 0.02 (below the
// critical 0.025). Until the waves arrive, the nodes near the ends feel
// forces far below any threshold, so freezing them saves work; the frozen
// motion is an approximation whose error must vanish with the threshold.
// Checks against the full scheme (threshold 0): the relative error of the
// final displacement decreases as the threshold goes 1e-3, 1e-5, 1e-7 and
// is below 1e-6 at 1e-7; at 1e-3 fewer than 80 % of the degrees of freedom
// are propagated on average (work is saved); at 1e-7 still fewer than 100 %.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/app/parameters.h>

#include "../tests.h"
#include "solid_scene.h"

#include <cmath>
#include <iostream>
#include <sstream>

using namespace dealii;
using namespace tissuefem;

namespace
{
  const char *scene = R"(
    set Dimension = 1
    subsection Geometry
      set Lower corner = 0
      set Upper corner = 1
      set Subdivisions = 40
    end
    subsection Materials
      set Model = linear elastic
      set Young's modulus = 1
      set Poisson's ratio = 0
      set Density = 1
    end
    subsection Boundary conditions
      set Dirichlet = 0: x: 0 | 1: x: 0
      set Initial displacement = 0.01*exp(-400*(x-0.5)^2)
    end
    subsection Time integration
      set Integrator = damped central difference
    end
  )";

  /// The average share of propagated degrees of freedom (percent) from
  /// the integrator's summary line.
  double
  propagated_share(const std::string &summary)
  {
    const auto   at = summary.find("on average ");
    const double share
      = at == std::string::npos ? 100. : std::stod(summary.substr(at + 11));
    return share;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ParameterHandler                 prm;
  declare_all_parameters(prm);
  prm.parse_input_from_string(scene);
  std::ostringstream discarded;
  std::streambuf    *screen = std::cout.rdbuf(discarded.rdbuf());

  auto run = [&](const double threshold, std::string &summary) {
    prm.enter_subsection("Time integration");
    prm.enter_subsection("Damped central difference");
    prm.set("Active region threshold", threshold);
    prm.leave_subsection();
    prm.leave_subsection();
    Vector<double> u;
    tissuefem_tests::run_to_end<1>(prm, 0.02, 0.15, &u, &summary);
    return u;
  };
  std::string          summary;
  const Vector<double> full = run(0., summary);
  std::vector<double>  errors, shares;
  for (const double threshold : {1e-3, 1e-5, 1e-7})
    {
      Vector<double> u = run(threshold, summary);
      u -= full;
      errors.push_back(u.linfty_norm() / full.linfty_norm());
      shares.push_back(propagated_share(summary));
    }
  std::cout.rdbuf(screen);
  std::ostringstream detail;
  detail << "errors " << errors[0] << ' ' << errors[1] << ' ' << errors[2]
         << ", propagated " << shares[0] << ' ' << shares[1] << ' ' << shares[2]
         << " %";
  tissuefem_tests::check(errors[0] > errors[1] && errors[1] > errors[2]
                           && errors[2] < 1e-6,
                         "active region: error falls with the threshold, "
                         "below 1e-6 at 1e-7",
                         detail.str());
  tissuefem_tests::check(shares[0] < 80. && shares[2] < 100.,
                         "active region: work saved (under 80 % of the "
                         "degrees of freedom propagated at 1e-3)",
                         detail.str());
  return tissuefem_tests::exit_status();
}
