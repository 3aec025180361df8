// The damped central difference (Jeffrey eq 11) on a single degree of
// freedom with a known solution: a 1D bar of one linear element, clamped at
// x = 0, linear elastic (E = 1, nu = 0, rho = 1), so that the free node
// obeys m u'' + c m u' + k u = 0 with the lumped mass m = 1/2 and k = 1
// (omega^2 = 2), started from u = 0.01 at rest. Its exact motion is
// u(t) = 0.01 e^{-ct/2} (cos w t + c/(2w) sin w t), w^2 = 2 - c^2/4. The
// errors at t = 1 for steps 0.05, 0.025, 0.0125 must decrease with observed
// order 2 (within 0.2), undamped and damped (c = 0.5); with a step ratio
// eta != 1 on the last step (end time not a multiple of the step) as well.

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
  const std::string scene = tissuefem_tests::one_element_bar(R"(
      set Integrator = damped central difference
)");

  double
  exact(const double c, const double t)
  {
    const double w = std::sqrt(2. - c * c / 4.);
    return 0.01 * std::exp(-c * t / 2.)
           * (std::cos(w * t) + c / (2. * w) * std::sin(w * t));
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ParameterHandler                 prm;
  declare_all_parameters(prm);
  prm.parse_input_from_string(scene);

  for (const double c : {0., 0.5})
    for (const double end_time : {1., 1.03})
      {
        prm.enter_subsection("Time integration");
        prm.enter_subsection("Damped central difference");
        prm.set("Damping ratio", c);
        prm.leave_subsection();
        prm.leave_subsection();
        std::vector<double> errors;
        // The integrator's report of the critical step goes to the screen
        // (std::cout), which is this test's compared output: discard it.
        std::ostringstream discarded;
        std::streambuf    *screen = std::cout.rdbuf(discarded.rdbuf());
        for (const double step : {0.05, 0.025, 0.0125})
          errors.push_back(std::abs(
            std::abs(tissuefem_tests::run_to_end<1>(prm, step, end_time))
            - std::abs(exact(c, end_time))));
        std::cout.rdbuf(screen);
        const double      order_1 = std::log2(errors[0] / errors[1]);
        const double      order_2 = std::log2(errors[1] / errors[2]);
        const std::string name    = "damping " + std::to_string(c).substr(0, 3)
                                 + ", end time "
                                 + std::to_string(end_time).substr(0, 4);
        tissuefem_tests::check(std::abs(order_1 - 2.) < 0.2
                                 && std::abs(order_2 - 2.) < 0.2,
                               name + ": observed order 2 within 0.2",
                               "orders " + std::to_string(order_1) + ", "
                                 + std::to_string(order_2));
      }
  return tissuefem_tests::exit_status();
}
