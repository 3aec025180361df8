// Organs under their own weight in one quasistatic step (issue: "a
// quasistatic run under a constant load gives up"). SOFA's Armadillo
// standing on its soles and hanging by its head, and SOFA's two livers
// hanging from their tops (data/), robust neo-Hookean, gravity 9.81, all
// asked for in a single step of size End time = 1:
// - with the default 'Load factor' (automatic: t / End time in a
//   quasistatic run), whose failed step is halved;
// - with 'Load factor = 1', the loads constant in time, carried by load
//   continuation (time/quasistatic.cc);
// - with 'Newton solver/Globalization = trust region'.
// Each run must reach t = 1, and there be in equilibrium: the clamp
// carries the whole weight, rho g V, with V summed from the tetrahedra's
// vertices here (a closed form, not a run), and no sideways force.

#include <deal.II/base/mpi.h>

#include <tissuefem/app/parameters.h>

#include "../tests.h"
#include "solid_scene.h"

#include <cmath>
#include <sstream>

using namespace tissuefem_tests;

namespace
{
  struct Organ
  {
    std::string name, mesh, clamp;
  };

  /// rho g V for rho = 1, g = 9.81: the volume from the vertices of each
  /// tetrahedron.
  double
  weight(const Triangulation<3> &mesh)
  {
    double volume = 0;
    for (const auto &cell : mesh.active_cell_iterators())
      {
        Tensor<2, 3> M;
        for (unsigned int k = 1; k <= 3; ++k)
          for (unsigned int i = 0; i < 3; ++i)
            M[i][k - 1] = cell->vertex(k)[i] - cell->vertex(0)[i];
        volume += std::abs(determinant(M)) / 6;
      }
    return 9.81 * volume;
  }

  void
  check_organ(const Organ       &organ,
              const std::string &variant,
              const std::string &settings)
  {
    ParameterHandler prm;
    tissuefem::declare_all_parameters(prm);
    prm.parse_input_from_string(
      "set Dimension = 3\n"
      "subsection Geometry\n"
      "  set Source = file\n"
      "  set Mesh file = "
      + std::string(SOURCE_DIR) + "/../../data/" + organ.mesh
      + "\n  set Boundary id predicates = 7: " + organ.clamp
      + "\nend\n"
        "subsection Materials\n"
        "  set Model = robust neo-Hookean\n"
        "  set Young's modulus = 3000\n"
        "  set Poisson's ratio = 0.3\n"
        "end\n"
        "subsection Boundary conditions\n"
        "  set Dirichlet = 7: xyz: 0; 0; 0\n"
        "  set Gravity = 0, -9.81, 0\n"
        "end\n"
        "subsection Time integration\n"
        "  set Integrator = quasistatic\n"
        "  set End time = 1\n"
        "  set Time step = 1\n"
        "end\n"
      + settings);
    const std::string  label = organ.name + ", " + variant;
    std::ostringstream muted;
    auto              *screen = std::cout.rdbuf(muted.rdbuf());
    std::string        error;
    double             lift = 0, sideways = 0, expected = 1;
    try
      {
        SolidScene<3> scene(prm);
        auto         &solid      = *scene.solid;
        time::Context context    = scene.context();
        auto          integrator = scene.integrator(prm);
        time::State   state;
        solid.initial_state(state.u, state.v);
        integrator->initialize(context, state);
        while (state.time < 1 - 1e-12)
          integrator->advance(state, 1.);
        const auto force = solid.reaction_forces(state.u, state.a, 1., {}, {7});
        lift             = force[1];
        sideways         = std::hypot(force[0], force[2]);
        expected         = weight(scene.triangulation);
      }
    catch (const std::exception &e)
      {
        error = e.what();
      }
    std::cout.rdbuf(screen);
    check(error.empty(), label + ": reaches t = 1", error);
    check_small(lift / expected - 1, 1e-8, label + ": clamp carries rho g V");
    check_small(sideways / expected,
                1e-8,
                label + ": no sideways force (over rho g V)");
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const std::vector<Organ>         organs
    = {{"Armadillo standing", "Armadillo_Tetra_4406.vtu", "y < -4.4"},
       {"Armadillo hanging", "Armadillo_Tetra_4406.vtu", "y > 8.5"},
       {"liver", "liver.msh", "y > 4.2"},
       {"liver2", "liver2.msh", "y > 0.45"}};
  for (const auto &organ : organs)
    {
      check_organ(organ, "default load factor", "");
      check_organ(organ,
                  "constant load (Load factor = 1)",
                  "subsection Boundary conditions\n"
                  "  set Load factor = 1\n"
                  "end\n");
      check_organ(organ,
                  "trust region",
                  "subsection Newton solver\n"
                  "  set Globalization = trust region\n"
                  "end\n");
    }
  return exit_status();
}
