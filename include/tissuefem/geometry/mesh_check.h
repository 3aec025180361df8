#pragma once

#include <deal.II/grid/tria.h>

#include <string>
#include <vector>

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

  /// What survey_gmsh() finds in a Gmsh file.
  struct GmshSurvey
  {
    /// Triangles (dim 2) or tetrahedra (dim 3) whose vertices are listed
    /// in inverted order (negative volume).
    unsigned int inverted = 0;
    /// Element numbers used by more than one element, in order of first
    /// repetition, and how many elements use each.
    std::vector<long>         repeated_numbers;
    std::vector<unsigned int> repeated_uses;
    /// Numbers of the simplices that list one node twice (degenerate:
    /// deal.II's reader would build a cell that connects a vertex to
    /// itself, which its debug build stops on).
    std::vector<long> repeated_node_elements;
  };

  /**
   * Surveys a Gmsh ASCII file (formats 1.0 and 2.x) for what deal.II's
   * reader passes over in silence: simplices in inverted order (it
   * reorients them), element numbers used twice (it numbers cells
   * itself) and simplices listing a node twice. Empty where the file cannot be
   * parsed (the reader reports that) or is of format 4.
   */
  GmshSurvey
  survey_gmsh(const std::string &file, const int dim);
} // namespace tissuefem::geometry
