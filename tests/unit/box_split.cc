// The simplex box with 'Tetrahedra per hexahedron = 6' (Kuhn's split, the
// split of SOFA's benchmark beams) and deal.II's 5: the number of cells
// (6 and 5 per hexahedron), every tetrahedron positive, the volume and the
// area of each boundary id those of the box (a face that did not match
// its neighbour's would add inner boundary), and the patch test: a scene
// whose every face is held at the homogeneous deformation u = A x
// reproduces it exactly at every node (the constant stress of a
// homogeneous deformation is in equilibrium; P1 holds linear fields).

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <tissuefem/app/parameters.h>

#include "../tests.h"
#include "solid_scene.h"

using namespace dealii;
using namespace tissuefem;

namespace
{
  void
  check(const unsigned int split)
  {
    // u = A x with A = [[0.02, 0.01, 0], [0, -0.01, 0.005], [0.003, 0, 0.01]].
    const std::string u
      = "0.02*x + 0.01*y; -0.01*y + 0.005*z; 0.003*x + 0.01*z";
    const std::string text = R"(
    set Dimension = 3
    subsection Geometry
      set Cell type                 = simplex
      set Tetrahedra per hexahedron = )"
                             + std::to_string(split) + R"(
      set Lower corner              = 0, 6, -2
      set Upper corner              = 4, 8, 2
      set Subdivisions              = 4, 3, 2
    end
    subsection Materials
      set Model           = neo-Hookean
      set Young's modulus = 1000
      set Poisson's ratio = 0.3
    end
    subsection Time integration
      set Integrator = quasistatic
      set End time   = 1
      set Time step  = 1
    end
    subsection Boundary conditions
      set Dirichlet = )" +
                             [&] {
                               std::string all;
                               for (unsigned int id = 0; id < 6; ++id)
                                 all += (id ? " | " : "") + std::to_string(id)
                                        + ": xyz: " + u;
                               return all;
                             }()
                             + R"(
    end
  )";
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string(text);
    tissuefem_tests::SolidScene<3> scene(prm);
    const auto                    &mesh = scene.triangulation;
    const std::string              name
      = std::to_string(split) + " tetrahedra per hexahedron";

    tissuefem_tests::check(mesh.n_active_cells() == split * 4 * 3 * 2,
                           name + ": " + std::to_string(split * 24) + " cells",
                           std::to_string(mesh.n_active_cells()));
    double              volume = 0, smallest = 1e300;
    std::vector<double> area(6, 0.);
    for (const auto &cell : mesh.active_cell_iterators())
      {
        volume += cell->measure();
        tissuefem_tests::lower(smallest, cell->measure());
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            area[face->boundary_id()] += face->measure();
      }
    tissuefem_tests::check(smallest > 0,
                           name + ": every tetrahedron positive",
                           std::to_string(smallest));
    tissuefem_tests::check_small(volume / 32 - 1, 1e-12, name + ": volume 32");
    const double face_area[6] = {8, 8, 16, 16, 8, 8}; // x, y, z faces
    double       worst        = 0;
    for (unsigned int id = 0; id < 6; ++id)
      tissuefem_tests::raise(worst, std::abs(area[id] / face_area[id] - 1));
    tissuefem_tests::check_small(worst,
                                 1e-12,
                                 name + ": area of each boundary id");

    auto run = scene.start(prm);
    run->advance_to(1.);
    const auto &dofs = scene.discretization->dof_handler;
    std::map<types::global_dof_index, Point<3>> points;
    DoFTools::map_dofs_to_support_points(*scene.discretization->mapping,
                                         dofs,
                                         points);
    const double A[3][3]
      = {{0.02, 0.01, 0}, {0, -0.01, 0.005}, {0.003, 0, 0.01}};
    const auto component = [&](const types::global_dof_index i) {
      return i % 3; // a P1 vertex's dofs are x, y, z in turn
    };
    worst = 0;
    for (const auto i : run->state.u.locally_owned_elements())
      {
        const unsigned int c     = component(i);
        double             exact = 0;
        for (unsigned int d = 0; d < 3; ++d)
          exact += A[c][d] * points[i][d];
        tissuefem_tests::raise(worst, std::abs(run->state.u[i] - exact));
      }
    tissuefem_tests::check_small(worst / 0.05,
                                 1e-10,
                                 name
                                   + ": patch test, the homogeneous "
                                     "deformation at every node");
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check(6);
  check(5);
  return tissuefem_tests::failures() == 0 ? 0 : 1;
}
