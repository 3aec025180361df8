// The tangled share of the volume (solid/self_overlap.h) on deformations
// whose answer is known by construction, on quadrilaterals, triangles,
// hexahedra and tetrahedra:
// - the identity and a rigid quarter turn: 0 (one to one, det F > 0);
// - a mirror image (x -> -x): 1 (det F < 0 everywhere);
// - the unit square (cube: times the thickness 0.1 in z) wrapped one and
//   a half times round an annulus, X -> r (cos 3 pi x, sin 3 pi x) with
//   r = 1 - 0.1 y: det F > 0 everywhere, but the angles of x < 1/3 and
//   x > 2/3 cover the same half annulus, where the winding number of the
//   deformed boundary is 2. On 30 cells along x (cell boundaries at x =
//   1/3 and 2/3) the tangled share is exactly 2/3: a fold-over no det F
//   test sees.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/app/parameters.h>
#include <tissuefem/solid/self_overlap.h>

#include "../tests.h"
#include "solid_scene.h"

#include <string>

using namespace dealii;
using namespace tissuefem;

namespace
{
  template <int dim>
  double
  tangled_share(const std::string &cells, const std::string &displacement)
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    const std::string upper = dim == 2 ? "1, 1" : "1, 1, 0.1";
    const std::string n     = dim == 2 ? "30, 3" : "30, 3, 1";
    prm.parse_input_from_string("set Dimension = " + std::to_string(dim)
                                + "\nsubsection Geometry\n set Cell type = "
                                + cells + "\n set Upper corner = " + upper
                                + "\n set Subdivisions = " + n
                                + "\nend\nsubsection Boundary conditions\n"
                                  " set Initial displacement = "
                                + displacement + "\nend\n");
    tissuefem_tests::SolidScene<dim> scene(prm);
    VectorType                       u, v, ghosted;
    scene.solid->initial_state(u, v);
    scene.discretization->initialize_vector(ghosted, true);
    ghosted = u;
    return solid::tangled_volume_fraction(*scene.discretization, ghosted);
  }


  template <int dim>
  void
  check_cells(const std::string &cells)
  {
    const std::string z    = dim == 3 ? "; 0" : "";
    const std::string name = std::to_string(dim) + "D " + cells;
    const std::string wrap = "(1 - 0.1*y)*cos(3*pi*x) - x; "
                             "(1 - 0.1*y)*sin(3*pi*x) - y"
                             + z;
    const std::string turn  = "-y - x; x - y" + z;
    const std::string minus = "-2*x; 0" + z;
    tissuefem_tests::check_small(tangled_share<dim>(cells, "0; 0" + z),
                                 1e-12,
                                 name + ", identity");
    tissuefem_tests::check_small(tangled_share<dim>(cells, turn),
                                 1e-12,
                                 name + ", quarter turn");
    tissuefem_tests::check_small(tangled_share<dim>(cells, minus) - 1,
                                 1e-12,
                                 name + ", mirror image: 1");
    tissuefem_tests::check_small(tangled_share<dim>(cells, wrap) - 2. / 3,
                                 1e-12,
                                 name + ", wrapped 1.5 times: 2/3");
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check_cells<2>("hypercube");
  check_cells<2>("simplex");
  check_cells<3>("hypercube");
  check_cells<3>("simplex");
  return tissuefem_tests::exit_status();
}
