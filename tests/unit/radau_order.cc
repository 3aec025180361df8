// The Radau IIA integrator (Jeffrey appendix D) on the single degree of
// freedom of central_difference_order: a 1D bar of one linear element,
// clamped at x = 0 (E = 1, nu = 0, rho = 1, lumped mass m = 1/2, k = 1,
// omega^2 = 2), started from u = 0.01 at rest, with mass-proportional
// damping c: u(t) = 0.01 e^{-ct/2} (cos w t + c/(2w) sin w t), w^2 = 2 -
// c^2/4. With fixed steps 0.1, 0.05, 0.025 the errors at t = 1 must
// decrease with observed order 5 (within 0.2) for each Jacobian kind
// (analytical, numerical, simplified), undamped and damped (c = 0.5).
// Then with the adaptive step: the error at t = 1 must fall with the
// tolerance (1e-4 -> 1e-7: at least 100 times smaller), a check of the
// error estimate and step control.

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
      set Integrator = Radau IIA
      subsection Radau IIA
        set Absolute tolerance = 1e-13
        set Absolute velocity tolerance = 1e-13
      end
)");

  double
  exact(const double c, const double t)
  {
    const double w = std::sqrt(2. - c * c / 4.);
    return 0.01 * std::exp(-c * t / 2.)
           * (std::cos(w * t) + c / (2. * w) * std::sin(w * t));
  }

  void
  set(ParameterHandler &prm, const std::string &name, const std::string &value)
  {
    prm.enter_subsection("Time integration");
    prm.enter_subsection("Radau IIA");
    prm.set(name, value);
    prm.leave_subsection();
    prm.leave_subsection();
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ParameterHandler                 prm;
  declare_all_parameters(prm);
  prm.parse_input_from_string(scene);

  for (const std::string jacobian : {"analytical", "numerical", "simplified"})
    for (const double c : {0., 0.5})
      {
        set(prm, "Jacobian", jacobian);
        set(prm, "Damping ratio", std::to_string(c));
        set(prm, "Adaptive step", "false");
        // The simplified Jacobian contracts by about 0.05 per iteration
        // here: the first step (no starting values from an earlier one)
        // needs more than the default 7 iterations to reach 1e-10, and a
        // step cut short would spoil the fixed-step sequence.
        set(prm, "Maximum Newton iterations", "30");
        set(prm, "Relative tolerance", "1e-10");
        std::vector<double> errors;
        for (const double step : {0.1, 0.05, 0.025})
          errors.push_back(
            std::abs(std::abs(tissuefem_tests::run_to_end<1>(prm, step, 1.))
                     - std::abs(exact(c, 1.))));
        const double      order_1 = std::log2(errors[0] / errors[1]);
        const double      order_2 = std::log2(errors[1] / errors[2]);
        const std::string name
          = jacobian + " Jacobian, damping " + std::to_string(c).substr(0, 3);
        tissuefem_tests::check(std::abs(order_1 - 5.) < 0.2
                                 && std::abs(order_2 - 5.) < 0.2,
                               name + ": observed order 5 within 0.2",
                               "orders " + std::to_string(order_1) + ", "
                                 + std::to_string(order_2));
      }

  // Adaptive: the error follows the tolerance.
  set(prm, "Jacobian", "analytical");
  set(prm, "Damping ratio", "0.5");
  set(prm, "Adaptive step", "true");
  set(prm, "Maximum Newton iterations", "7");
  std::vector<double> errors;
  for (const auto &[relative, absolute] :
       {std::pair<std::string, std::string>{"1e-4", "1e-6"}, {"1e-7", "1e-9"}})
    {
      set(prm, "Relative tolerance", relative);
      set(prm, "Absolute tolerance", absolute);
      set(prm, "Absolute velocity tolerance", absolute);
      errors.push_back(
        std::abs(std::abs(tissuefem_tests::run_to_end<1>(prm, 0.5, 1.))
                 - std::abs(exact(0.5, 1.))));
    }
  tissuefem_tests::check(errors[1] < 1e-2 * errors[0] && errors[0] < 1e-5,
                         "adaptive step: error below 0.1 % of the amplitude "
                         "at tolerance 1e-4 and 100 times smaller at 1e-7",
                         "errors " + std::to_string(errors[0]) + ", "
                           + std::to_string(errors[1]));
  return tissuefem_tests::exit_status();
}
