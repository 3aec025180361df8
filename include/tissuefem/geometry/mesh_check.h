#pragma once

#include <deal.II/grid/tria.h>

#include <string>

namespace tissuefem::geometry
{
  using namespace dealii;

  /**
   * Checks a mesh read from @p file before anything is computed on it, and
   * throws InputError naming the file, what is wrong and the first few
   * cells (ids in the order deal.II holds them, 0-based) or vertices
   * concerned:
   * - a vertex coordinate that is not a finite number;
   * - duplicate vertices: two vertices of cells closer than 1e-10 times
   *   the mesh's extent (the mesh would be cut along them and its parts
   *   move independently, which no error message would reveal later);
   * - a cell with zero or negative volume (degenerate or inverted): signed
   *   volume from the vertex positions for simplices, the Jacobian
   *   determinant at the vertices for quadrilaterals and hexahedra.
   * Mixed cell types, missing vertices, truncated files and the wrong
   * dimension are found while reading (vtu_reader.cc, deal.II's GridIn).
   */
  template <int dim>
  void
  check_mesh(const Triangulation<dim> &triangulation, const std::string &file);

  /**
   * The number of triangles (@p dim = 2) or tetrahedra (3) of a Gmsh ASCII
   * file (formats 1.0 and 2.x) whose vertices are listed in inverted order
   * (negative volume). deal.II's reader reorients them silently; tissuefem
   * says so. 0 where the file cannot be parsed (the reader reports that).
   */
  unsigned int
  count_inverted_gmsh_simplices(const std::string &file, const int dim);
} // namespace tissuefem::geometry
