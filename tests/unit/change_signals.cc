// The solid's announcements of changes (solid/change_signals.h): a grasp, a
// release and a mesh adaptation each emit about_to_change, then changed, once;
// inside changed the new constraints are in effect (the held vertex gets its
// prescribed value) and, in an adaptation, the state has already moved to
// the new mesh (its size is the new number of unknowns and its largest value,
// 0.1 at the corner x = 1 of the field u_x = 0.1 x^2, is kept: bilinear
// interpolation onto refined cells keeps the nodal values it had).

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <tissuefem/adaptation/mesh_adaptation.h>
#include <tissuefem/app/parameters.h>

#include "../tests.h"
#include "solid_scene.h"

#include <cmath>
#include <string>
#include <vector>

using namespace dealii;
using namespace tissuefem;

namespace
{
  const char *scene = R"(
    set Dimension = 2
    subsection Geometry
      set Lower corner = 0, 0
      set Upper corner = 1, 1
      set Subdivisions = 4, 4
    end
    subsection Materials
      set Model = linear elastic
      set Young's modulus = 1
      set Poisson's ratio = 0.3
    end
    subsection Boundary conditions
      set Dirichlet = 0: xy: 0; 0
      set Initial displacement = 0.1*x*x; 0
    end
    subsection Mesh refinement
      set Indicator = Kelly
      set Refine fraction = 0.3
      set Coarsen fraction = 0
    end
  )";
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ParameterHandler                 prm;
  declare_all_parameters(prm);
  prm.parse_input_from_string(scene);
  tissuefem_tests::SolidScene<2> scene_objects(prm);
  auto                          &solid = *scene_objects.solid;

  std::vector<std::string> events;
  VectorType               u, v;
  solid.initial_state(u, v);
  double held_value = 0;
  // The vertex at (1, 0.5) of the 5 x 5 vertices, x fastest.
  const std::vector<unsigned int>          held = {14};
  const boost::signals2::scoped_connection before
    = solid.signals.about_to_change.connect(
      [&]() { events.push_back("about to change"); });
  const boost::signals2::scoped_connection after
    = solid.signals.changed.connect([&]() {
        events.push_back("changed");
        VectorType w;
        solid.initialize_vector(w);
        solid.apply_dirichlet_values(1., w);
        held_value = w.linfty_norm();
      });

  solid.hold(
    held,
    [](const double t) {
      Tensor<1, 2> d;
      d[0] = 0.05 * t;
      return d;
    },
    u);
  // At t = 1 the vertex starts at 0.1 * 1^2 and moves by 0.05.
  tissuefem_tests::check(events.size() == 2 && events[0] == "about to change"
                           && events[1] == "changed"
                           && std::abs(held_value - 0.15) < 1e-14,
                         "grasp: announced before and after, the held value "
                         "in effect when told");
  events.clear();
  solid.release();
  tissuefem_tests::check(events.size() == 2 && events[0] == "about to change"
                           && events[1] == "changed",
                         "release: announced before and after");

  events.clear();
  const auto         adaptation = scene_objects.mesh_adaptation(prm);
  const unsigned int old_dofs   = solid.n_dofs();
  unsigned int       seen_size  = 0;
  double             seen_max   = 0;
  const boost::signals2::scoped_connection state_seen
    = solid.signals.changed.connect([&]() {
        seen_size = u.size();
        seen_max  = u.linfty_norm();
      });
  const bool adapted = adaptation->adapt(u, 0., 0.1, {&u});
  tissuefem_tests::check(adapted && solid.n_dofs() > old_dofs
                           && events.size() == 2 && seen_size == solid.n_dofs()
                           && std::abs(seen_max - 0.1) < 1e-14,
                         "adaptation: announced once; the state is on the "
                         "new mesh when told");
  return tissuefem_tests::exit_status();
}
