// 'Geometry/Mesh distribution = distributed' on two processes, against the
// same scene with the mesh shared and against closed forms: a box of
// 12 x 3 x 3 hexahedra, each cut into 6 tetrahedra (648 cells).
// - Each process holds fewer cells than the whole, owns the same cells as
//   with the shared mesh (the same METIS partition), and its mesh takes
//   less memory.
// - The cells of all processes add up to the whole mesh, the boundary faces
//   by id to the box's (2 triangles per square: 18 on x = 0 and x = 6, 72 on
//   each other face), the diameter to the box's diagonal.
// - Probes at 200 random points (fixed seed), at 64 grid points (on faces
//   and vertices shared by cells) and on the faces between cells of
//   different processes (their centres and a vertex each) read a linear
//   field exactly, once each: the P1 interpolant of u = A x + b is u
//   itself.

#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <tissuefem/app/parameters.h>
#include <tissuefem/geometry/distribution.h>
#include <tissuefem/geometry/geometry.h>
#include <tissuefem/output/probes.h>
#include <tissuefem/scene/scene.h>

#include <cmath>
#include <random>
#include <set>

#include "../tests.h"

using namespace dealii;
using namespace tissuefem;

namespace
{
  std::unique_ptr<Scene<3>>
  make_scene(ParameterHandler &prm, const std::string &distribution)
  {
    declare_all_parameters(prm);
    prm.parse_input_from_string(R"(
    set Dimension = 3
    subsection Geometry
      set Cell type                 = simplex
      set Tetrahedra per hexahedron = 6
      set Lower corner              = 0, 6, -2
      set Upper corner              = 6, 7.5, -0.5
      set Subdivisions              = 12, 3, 3
      set Mesh distribution         = )"
                                + distribution + R"(
    end
    subsection Boundary conditions
      set Dirichlet = 0: xyz: 0; 0; 0
    end
    )");
    return std::make_unique<Scene<3>>(prm);
  }


  /// u = A x + b.
  class Linear : public Function<3>
  {
  public:
    Linear()
        : Function<3>(3)
    {
    }

    double
    value(const Point<3> &p, const unsigned int c) const override
    {
      static const double A[3][3]
        = {{0.02, 0.01, 0}, {0, -0.01, 0.005}, {0.003, 0, 0.01}};
      static const double b[3] = {0.1, -0.2, 0.3};
      double              u    = b[c];
      for (unsigned int d = 0; d < 3; ++d)
        u += A[c][d] * p[d];
      return u;
    }
  };


  /// The centres of the cells this process owns.
  std::set<std::pair<double, std::pair<double, double>>>
  owned_centres(const Triangulation<3> &mesh)
  {
    std::set<std::pair<double, std::pair<double, double>>> centres;
    for (const auto &cell : mesh.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          // Rounded: both meshes come from the same vertices, but their
          // centres are summed in the order of each cell's vertices.
          const Point<3> c = cell->center();
          const auto     r
            = [](const double x) { return std::round(x * 1e9) / 1e9; };
          centres.insert({r(c[0]), {r(c[1]), r(c[2])}});
        }
    return centres;
  }


  /// The largest error of the probes over @p points, over all processes.
  double
  probe_error(const Scene<3> &scene, const std::vector<Point<3>> &points)
  {
    const auto &d = scene.solid->get_discretization();
    VectorType  owned, ghosted;
    d.initialize_vector(owned);
    d.initialize_vector(ghosted, true);
    VectorTools::interpolate(*d.mapping, d.dof_handler, Linear(), owned);
    ghosted = owned;
    const output::Probes<3> probes(points, *d.mapping, d.dof_handler, "test");
    const auto              values = probes.evaluate(ghosted);
    double                  worst  = 0;
    for (unsigned int p = 0; p < points.size(); ++p)
      for (unsigned int c = 0; c < 3; ++c)
        worst = std::max(worst,
                         std::abs(values[p][c] - Linear().value(points[p], c)));
    return worst;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   comm = MPI_COMM_WORLD;
  // Every check below is of global figures (reduced over processes).
  tissuefem_tests::OneWriter one_writer;
  ParameterHandler           prm_shared, prm_distributed;
  const auto                 shared = make_scene(prm_shared, "shared");
  const auto  distributed = make_scene(prm_distributed, "distributed");
  const auto &whole = shared->triangulation, &part = distributed->triangulation;

  tissuefem_tests::check(!geometry::holds_whole_mesh<3>(part)
                           && geometry::holds_whole_mesh<3>(whole),
                         "the distributed mesh is fully distributed");
  tissuefem_tests::check(part.n_global_active_cells() == 648
                           && whole.n_global_active_cells() == 648,
                         "648 cells in all");
  tissuefem_tests::check(Utilities::MPI::max(part.n_active_cells(), comm) < 648,
                         "no process holds every cell");
  tissuefem_tests::check(
    Utilities::MPI::sum(part.n_locally_owned_active_cells(), comm) == 648,
    "the processes' own cells add up to the whole mesh");
  tissuefem_tests::check(
    Utilities::MPI::min(owned_centres(part) == owned_centres(whole) ? 1 : 0,
                        comm)
      == 1,
    "each process owns the cells it owns on the shared "
    "mesh");
  tissuefem_tests::check(Utilities::MPI::max(part.memory_consumption(), comm)
                           < Utilities::MPI::min(whole.memory_consumption(),
                                                 comm),
                         "each process's mesh takes less memory");

  const std::string faces = "boundary faces by id: 0 (18) 1 (18) 2 (72) "
                            "3 (72) 4 (72) 5 (72)";
  tissuefem_tests::check(geometry::describe_boundary_ids<3>(part) == faces
                           && geometry::describe_boundary_ids<3>(whole)
                                == faces,
                         "boundary faces by id as the box's",
                         geometry::describe_boundary_ids<3>(part));
  const double diagonal = std::sqrt(6. * 6 + 1.5 * 1.5 + 1.5 * 1.5);
  tissuefem_tests::check_small((geometry::diameter<3>(part) - diagonal)
                                 / diagonal,
                               1e-14,
                               "diameter of the distributed mesh: the box's "
                               "diagonal");
  tissuefem_tests::check_small((geometry::diameter<3>(whole) - diagonal)
                                 / diagonal,
                               1e-14,
                               "diameter of the shared mesh: the box's "
                               "diagonal");

  std::vector<Point<3>>                  points;
  std::mt19937                           random(2026);
  std::uniform_real_distribution<double> unit(0, 1);
  for (unsigned int i = 0; i < 200; ++i)
    points.emplace_back(6 * unit(random),
                        6 + 1.5 * unit(random),
                        -2 + 1.5 * unit(random));
  for (unsigned int i = 0; i < 16; ++i)
    for (unsigned int j = 0; j < 4; ++j)
      points.emplace_back(0.4 * i, 6 + 0.5 * j, -2 + 0.25 * (i % 7));
  // And the centres and vertices of the faces between cells of different
  // processes, which two processes' cells contain.
  std::vector<Point<3>> between;
  for (const auto &cell : part.active_cell_iterators())
    if (cell->is_locally_owned())
      for (const unsigned int f : cell->face_indices())
        if (!cell->at_boundary(f) && cell->neighbor(f)->is_ghost())
          {
            between.push_back(cell->face(f)->center());
            between.push_back(cell->face(f)->vertex(0));
          }
  for (const auto &list : Utilities::MPI::all_gather(comm, between))
    points.insert(points.end(), list.begin(), list.end());
  tissuefem_tests::check(points.size() > 300,
                         "there are faces between processes' cells");
  for (const auto &[name, scene] : {std::pair{"distributed", distributed.get()},
                                    std::pair{"shared", shared.get()}})
    tissuefem_tests::check_small(probe_error(*scene, points),
                                 1e-13,
                                 std::string("probes on the ") + name
                                   + " mesh read u = A x + b");
  return tissuefem_tests::failures() == 0 ? 0 : 1;
}
