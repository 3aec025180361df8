// Jeffrey's active region (node freezing, report section 3) is stable at
// any threshold. A linear elastic block of 320 linear tetrahedra
// (E = 1, nu = 0.3, rho = 1), clamped at x = 0, starts from noisy
// displacements (each free entry uniform in +-0.02, cell size 0.25; three
// fixed seeds) at rest, without damping or loads, and runs 1500 steps of
// the damped central difference at 80 % of its estimated critical step,
// where the highest modes are fast. With thresholds from 1e-6 (nearly
// every node propagated) to 10 (nearly none), for every seed:
//   - no run stops (the integrator throws on a non-finite displacement,
//     one beyond 1000 times the body's size, or a 1e4-fold energy growth);
//   - the stored plus kinetic energy (velocity (u_n+1 - u_n)/dt) never
//     exceeds 1.1 times the largest of the run without freezing, initial
//     energy included: a freeze is allowed only where it does not raise
//     the scheme's conserved energy, exactly so for this linear model;
//   - the final displacement's relative difference from the run without
//     freezing is below 1e-3 at the threshold 1e-6, the smallest.
// (The muscle scene, where an earlier freezing rule blew up, is the test
// studies/active_region.)

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/app/parameters.h>

#include "../tests.h"
#include "solid_scene.h"

#include <iostream>
#include <random>
#include <sstream>

using namespace dealii;
using namespace tissuefem;

namespace
{
  const char *scene = R"(
    set Dimension = 3
    subsection Geometry
      set Cell type    = simplex
      set Lower corner = 0, 0, 0
      set Upper corner = 1, 1, 1
      set Subdivisions = 4, 4, 4
    end
    subsection Materials
      set Model = linear elastic
      set Young's modulus = 1
      set Poisson's ratio = 0.3
      set Density = 1
    end
    subsection Boundary conditions
      set Dirichlet = 0: xyz: 0; 0; 0
    end
    subsection Time integration
      set Integrator = damped central difference
    end
  )";

  struct Run
  {
    double         largest_energy = 0;
    double         critical_step  = 0;
    bool           stopped        = false;
    Vector<double> u;
  };

  /// Runs @p steps steps from the noisy start of @p seed; a step of 0
  /// only reads the critical step.
  Run
  run(ParameterHandler  &prm,
      const double       threshold,
      const unsigned int seed,
      const double       step,
      const unsigned int steps)
  {
    prm.enter_subsection("Time integration");
    prm.set("Time step", step > 0 ? step : 1e-6);
    prm.enter_subsection("Damped central difference");
    prm.set("Active region threshold", threshold);
    prm.leave_subsection();
    prm.leave_subsection();
    tissuefem_tests::SolidScene<3> scene(prm);
    auto                          &solid      = *scene.solid;
    time::Context                  context    = scene.context();
    auto                           integrator = scene.integrator(prm);
    time::State                    state;
    solid.initial_state(state.u, state.v);
    std::mt19937                           random(seed);
    std::uniform_real_distribution<double> noise(-0.02, 0.02);
    for (const auto i : state.u.locally_owned_elements())
      state.u[i] = noise(random);
    state.u.compress(VectorOperation::insert);
    solid.apply_dirichlet_values(0., state.u);

    std::ostringstream screen;
    std::streambuf    *old = std::cout.rdbuf(screen.rdbuf());
    Run                result;
    try
      {
        integrator->initialize(context, state);
        result.largest_energy  = solid.stored_energy(state.u);
        const std::string text = screen.str();
        const auto        at   = text.find("critical step ");
        result.critical_step   = std::stod(text.substr(at + 14));
        for (unsigned int k = 0; k < steps; ++k)
          {
            integrator->advance(state, 1e9);
            result.largest_energy = std::max(result.largest_energy,
                                             solid.stored_energy(state.u)
                                               + solid.kinetic_energy(state.v));
          }
      }
    catch (const std::exception &)
      {
        result.stopped = true;
      }
    std::cout.rdbuf(old);
    result.u = Vector<double>(state.u);
    return result;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ParameterHandler                 prm;
  declare_all_parameters(prm);
  prm.parse_input_from_string(scene);

  const unsigned int steps  = 1500;
  bool               stable = true, bounded = true, accurate = true;
  std::ostringstream detail;
  for (const unsigned int seed : {1u, 2u, 3u})
    {
      const double step = 0.8 * run(prm, 0., seed, 0., 0).critical_step;
      const Run    full = run(prm, 0., seed, step, steps);
      stable            = stable && !full.stopped;
      for (const double threshold : {1e-6, 1e-4, 1e-3, 1e-2, 1e-1, 1., 10.})
        {
          const Run      frozen = run(prm, threshold, seed, step, steps);
          Vector<double> difference(frozen.u);
          difference -= full.u;
          const double ratio = frozen.largest_energy / full.largest_energy;
          const double error = difference.l2_norm() / full.u.l2_norm();
          stable             = stable && !frozen.stopped;
          bounded            = bounded && ratio <= 1.1;
          if (threshold == 1e-6)
            accurate = accurate && error < 1e-3;
          detail << " seed " << seed << " threshold " << threshold
                 << ": energy ratio " << ratio << ", error " << error
                 << (frozen.stopped ? ", stopped" : "") << ';';
        }
    }
  tissuefem_tests::check(stable,
                         "active region: no run stops, at any threshold",
                         detail.str());
  tissuefem_tests::check(bounded,
                         "active region: energy never above 1.1 times the "
                         "largest without freezing",
                         detail.str());
  tissuefem_tests::check(accurate,
                         "active region: within 1e-3 of the exact scheme at "
                         "threshold 1e-6",
                         detail.str());
  return tissuefem_tests::exit_status();
}
