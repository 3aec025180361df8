// Blocks of the invertible neo-Hookean model recover their rest shape from
// any start: nodes scrambled by up to two cell sizes, or the block collapsed
// to a plane, a line or a point, on hexahedra and on tetrahedra. Backward
// Euler from rest, no loads and no constraints; the exact answer is the
// rest shape up to a rigid motion, so the measure is the largest nodal
// distance from the best rigidly moved rest shape (rotation with det +1:
// a mirror image does not count), which must fall below 1e-3 (the block
// is 1 long).

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/base/application.h>
#include <tissuefem/solid/quantities.h>

#include <iostream>
#include <sstream>

#include "../tests.h"
#include "solid_scene.h"

using namespace dealii;
using namespace tissuefem;

namespace
{
  double
  recover(const std::string &cells, const std::string &start)
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string(R"(
      set Dimension = 3
      subsection Geometry
        set Cell type    = )" + cells
                                + R"(
        set Subdivisions = 4, 4, 4
      end
      subsection Materials
        set Model           = invertible neo-Hookean
        set Young's modulus = 1000
        set Poisson's ratio = 0.3
        set Density         = 1
      end
      subsection Boundary conditions
        set Initial displacement = )"
                                + start + R"(
      end
      subsection Time integration
        set Integrator = backward Euler
        set Time step  = 0.02
      end
    )");
    tissuefem_tests::SolidScene<3> scene(prm);
    auto                          &solid      = *scene.solid;
    time::Context                  context    = scene.context();
    auto                           integrator = scene.integrator(prm);
    time::State                    state;
    solid.initial_state(state.u, state.v);
    integrator->initialize(context, state);
    while (state.time < 3 - 1e-9)
      integrator->advance(state, 3.);
    return solid::distance_from_rest_shape(*scene.discretization, state.u);
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  // Two cell sizes are 0.5; the phases make the three components look
  // unrelated from node to node.
  const std::vector<std::pair<std::string, std::string>> starts
    = {{"scrambled",
        "0.5*sin(9173.1*x + 5417.3*y + 3319.7*z); "
        "0.5*sin(7351.9*x + 8111.3*y + 2273.1*z); "
        "0.5*sin(4409.7*x + 6073.9*y + 9931.3*z)"},
       {"collapsed to a plane", "0; 0; 0.5 - z"},
       {"collapsed to a line", "0.5 - x; 0.5 - y; 0"},
       {"collapsed to a point", "0.5 - x; 0.5 - y; 0.5 - z"}};
  for (const std::string cells : {"hypercube", "simplex"})
    for (const auto &[name, start] : starts)
      {
        double distance = 1e300;
        // The run's screen output (step halvings) stays out of the
        // compared output.
        std::ostringstream muted;
        auto              *screen = std::cout.rdbuf(muted.rdbuf());
        std::string        error;
        try
          {
            distance = recover(cells, start);
          }
        catch (const std::exception &e)
          {
            error = e.what();
          }
        std::cout.rdbuf(screen);
        if (!error.empty())
          std::cout << "  " << error << '\n';
        tissuefem_tests::check_small(distance,
                                     1e-3,
                                     cells + ", " + name
                                       + ": distance from the rest shape");
      }
  return tissuefem_tests::exit_status();
}
