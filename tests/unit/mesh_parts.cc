// Face-connected parts of a mesh (geometry/mesh_parts.h), which decide
// whether a quasistatic scene is held. Expected counts: by construction
// for the generated meshes (two cubes apart, touching at an edge only, or
// sharing a face; a cube with hanging faces), and for the meshes others
// made, from an independent count (a union-find over the sorted vertex
// triples of the tetrahedra's faces, in Python, over the files as they
// are): SOFA's liver 1 part, Armadillo 1, 6_tetra_bad 6 (its six
// tetrahedra share no face).

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/tria.h>

#include <tissuefem/geometry/mesh_parts.h>
#include <tissuefem/geometry/vtu_reader.h>

#include "../tests.h"

#include <fstream>
#include <string>

using namespace dealii;
using namespace tissuefem;

namespace
{
  /// Two unit cubes merged, the second shifted by @p shift.
  unsigned int
  two_cubes(const Point<3> &shift)
  {
    Triangulation<3> a, b, both;
    GridGenerator::hyper_cube(a);
    GridGenerator::hyper_rectangle(b, shift, shift + Point<3>(1, 1, 1));
    GridGenerator::merge_triangulations(a, b, both);
    return geometry::MeshParts<3>(both).n_parts();
  }

  unsigned int
  gmsh_parts(const std::string &name)
  {
    Triangulation<3> mesh;
    GridIn<3>        in(mesh);
    std::ifstream    file(std::string(SOURCE_DIR) + "/../../data/" + name);
    in.read_msh(file);
    return geometry::MeshParts<3>(mesh).n_parts();
  }
} // namespace


int
main()
{
  tissuefem_tests::check(two_cubes(Point<3>(3, 0, 0)) == 2,
                         "two cubes apart: 2 parts");
  tissuefem_tests::check(two_cubes(Point<3>(1, 1, 0)) == 2,
                         "two cubes touching at an edge: 2 parts");
  tissuefem_tests::check(two_cubes(Point<3>(1, 0, 0)) == 1,
                         "two cubes sharing a face: 1 part");

  Triangulation<3> refined;
  GridGenerator::subdivided_hyper_cube(refined, 2);
  refined.begin_active()->set_refine_flag();
  refined.execute_coarsening_and_refinement();
  const geometry::MeshParts<3> parts(refined);
  tissuefem_tests::check(parts.n_parts() == 1 && parts.first_cell[0] == 0,
                         "a cube with hanging faces: 1 part");

  tissuefem_tests::check(gmsh_parts("liver.msh") == 1,
                         "SOFA liver.msh: 1 part");
  tissuefem_tests::check(gmsh_parts("6_tetra_bad.msh") == 6,
                         "SOFA 6_tetra_bad.msh: 6 parts");
  Triangulation<3> armadillo;
  geometry::read_vtu(std::string(SOURCE_DIR)
                       + "/../../data/Armadillo_Tetra_4406.vtu",
                     armadillo);
  tissuefem_tests::check(armadillo.n_active_cells() == 4406
                           && geometry::MeshParts<3>(armadillo).n_parts() == 1,
                         "SOFA Armadillo_Tetra_4406.vtu: 4406 cells, 1 part");
  return tissuefem_tests::exit_status();
}
