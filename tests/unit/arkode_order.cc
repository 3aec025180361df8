// The ARKode integrator on the single degree of freedom of radau_order: a
// 1D bar of one linear element, clamped at x = 0 (E = 1, nu = 0, rho = 1,
// lumped mass m = 1/2, k = 1, omega^2 = 2), started from u = 0.01 at rest,
// with mass-proportional damping c = 0.5: u(t) = 0.01 e^{-ct/2} (cos w t +
// c/(2w) sin w t), w^2 = 2 - c^2/4. With fixed steps 0.1, 0.05, 0.025 the
// errors at t = 1 must decrease with the observed order of the method
// table (within 0.2): explicit orders 2 and 4, implicit orders 3 and 4.
// Then with the adaptive step: for both methods the error at t = 1 must
// fall at least 100 times when the tolerances fall 1000 times.

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
      set Integrator = ARKode
      subsection ARKode
        set Damping ratio = 0.5
      end
)");

  double
  exact(const double t)
  {
    const double c = 0.5, w = std::sqrt(2. - c * c / 4.);
    return 0.01 * std::exp(-c * t / 2.)
           * (std::cos(w * t) + c / (2. * w) * std::sin(w * t));
  }

  void
  set(ParameterHandler &prm, const std::string &name, const std::string &value)
  {
    prm.enter_subsection("Time integration");
    prm.enter_subsection("ARKode");
    prm.set(name, value);
    prm.leave_subsection();
    prm.leave_subsection();
  }

  double
  error(ParameterHandler &prm, const double step)
  {
    return std::abs(std::abs(tissuefem_tests::run_to_end<1>(prm, step, 1.))
                    - std::abs(exact(1.)));
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

  for (const auto &[method, order] :
       std::vector<std::pair<std::string, unsigned int>>{
         {"explicit", 2}, {"explicit", 4}, {"implicit", 3}, {"implicit", 4}})
    {
      set(prm, "Method", method);
      set(prm, "Order", std::to_string(order));
      set(prm, "Adaptive step", "false");
      // Newton must converge far below the discretization error.
      set(prm, "Relative tolerance", "1e-10");
      set(prm, "Absolute tolerance", "1e-14");
      set(prm, "Absolute velocity tolerance", "1e-14");
      std::vector<double> errors;
      for (const double step : {0.1, 0.05, 0.025})
        errors.push_back(error(prm, step));
      const double order_1 = std::log2(errors[0] / errors[1]);
      const double order_2 = std::log2(errors[1] / errors[2]);
      std::cout.rdbuf(screen);
      tissuefem_tests::check(std::abs(order_1 - order) < 0.2
                               && std::abs(order_2 - order) < 0.2,
                             method + " order " + std::to_string(order)
                               + ": observed order within 0.2",
                             "orders " + std::to_string(order_1) + ", "
                               + std::to_string(order_2));
      std::cout.rdbuf(discarded.rdbuf());
    }

  set(prm, "Order", "4");
  set(prm, "Adaptive step", "true");
  for (const std::string method : {"explicit", "implicit"})
    {
      set(prm, "Method", method);
      std::vector<double> errors;
      for (const auto &[relative, absolute] :
           {std::pair<std::string, std::string>{"1e-4", "1e-6"},
            {"1e-7", "1e-9"}})
        {
          set(prm, "Relative tolerance", relative);
          set(prm, "Absolute tolerance", absolute);
          set(prm, "Absolute velocity tolerance", absolute);
          errors.push_back(error(prm, 0.5));
        }
      std::cout.rdbuf(screen);
      tissuefem_tests::check(errors[1] < 1e-2 * errors[0] && errors[0] < 1e-5,
                             method
                               + " adaptive: error below 0.1 % of the "
                                 "amplitude at tolerance 1e-4 and 100 times "
                                 "smaller at 1e-7",
                             "errors " + std::to_string(errors[0]) + ", "
                               + std::to_string(errors[1]));
      std::cout.rdbuf(discarded.rdbuf());
    }
  std::cout.rdbuf(screen);
  return tissuefem_tests::exit_status();
}
