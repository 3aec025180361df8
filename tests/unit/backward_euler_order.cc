// Backward Euler on the single degree of freedom of
// central_difference_order, with the consistent mass this integrator uses:
// a 1D bar of one linear element, clamped at x = 0 (E = 1, nu = 0, rho =
// 1), so that the free node obeys m u'' + k u = 0 with m = 1/3 and k = 1
// (omega^2 = 3), started from u = 0.01 at rest: u(t) = 0.01 cos(omega t).
// The errors at t = 1 for steps 0.02, 0.01, 0.005 must decrease with
// observed order 1 (within 0.2). With 'Adaptive step' the local error
// estimate (against the trapezoidal rule) is O(h^2), so steps scale as
// tol^(1/2) and so does the global error of a first-order method: the
// error at t = 1 for tolerances 1e-3 and 1e-5 (relative; absolute 100
// times smaller) must fall as tol^p with p = 1/2 within 0.2.

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
      set Integrator = backward Euler
)");

  double
  exact(const double t)
  {
    return 0.01 * std::cos(std::sqrt(3.) * t);
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ParameterHandler                 prm;
  declare_all_parameters(prm);
  prm.parse_input_from_string(scene);
  std::vector<double> errors;
  std::ostringstream  discarded;
  std::streambuf     *screen = std::cout.rdbuf(discarded.rdbuf());
  for (const double step : {0.02, 0.01, 0.005})
    errors.push_back(std::abs(tissuefem_tests::run_to_end<1>(prm, step, 1.)
                              - std::abs(exact(1.))));
  std::vector<double> adaptive_errors;
  prm.enter_subsection("Time integration");
  prm.enter_subsection("Backward Euler");
  prm.set("Adaptive step", true);
  for (const double tolerance : {1e-3, 1e-5})
    {
      prm.set("Relative tolerance", tolerance);
      prm.set("Absolute tolerance", tolerance / 100);
      prm.set("Absolute velocity tolerance", tolerance / 100);
      prm.leave_subsection();
      prm.leave_subsection();
      adaptive_errors.push_back(std::abs(
        tissuefem_tests::run_to_end<1>(prm, 0.25, 1.) - std::abs(exact(1.))));
      prm.enter_subsection("Time integration");
      prm.enter_subsection("Backward Euler");
    }
  prm.leave_subsection();
  prm.leave_subsection();
  std::cout.rdbuf(screen);
  const double exponent
    = std::log(adaptive_errors[0] / adaptive_errors[1]) / std::log(100.);
  tissuefem_tests::check(std::abs(exponent - 0.5) < 0.2,
                         "adaptive backward Euler: error ~ tolerance^(1/2) "
                         "within 0.2 in the exponent",
                         "exponent " + std::to_string(exponent) + ", errors "
                           + std::to_string(adaptive_errors[0]) + ", "
                           + std::to_string(adaptive_errors[1]));
  const double order_1 = std::log2(errors[0] / errors[1]);
  const double order_2 = std::log2(errors[1] / errors[2]);
  tissuefem_tests::check(std::abs(order_1 - 1.) < 0.2
                           && std::abs(order_2 - 1.) < 0.2,
                         "backward Euler: observed order 1 within 0.2",
                         "orders " + std::to_string(order_1) + ", "
                           + std::to_string(order_2));
  return tissuefem_tests::exit_status();
}
