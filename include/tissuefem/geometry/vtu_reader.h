#pragma once

#include <deal.II/grid/tria.h>

#include <string>

namespace tissuefem::geometry
{
  using namespace dealii;

  /**
   * Reads a mesh in VTK's XML UnstructuredGrid format (.vtu, one Piece,
   * ASCII data only, as SOFA ships organ meshes) into the empty
   * @p triangulation. deal.II 9.4's GridIn cannot read .vtu.
   *
   * Cells are tetrahedra (VTK type 10) or hexahedra (12) in 3D, triangles
   * (5) or quadrilaterals (9) in 2D, where the points' z must be constant.
   * An integer CellData array named "MaterialIds", "material_id",
   * "materialID" or "gmsh:physical" (the first one present) gives the cells
   * their material ids (0 without one) and gives boundary faces that the
   * file lists as cells of one dimension less (triangles or quadrilaterals
   * in 3D, lines in 2D) their boundary ids; such faces that lie inside the
   * mesh are ignored, as are all other lower-dimensional cells. Cells that
   * the file orients negatively are reoriented. Points that no cell uses
   * are dropped.
   *
   * Throws InputError, naming the file and the problem in one line, for
   * binary or appended data, missing arrays, wrong counts, non-numeric
   * text, point indices out of range, ids outside 0..254, unsupported cell
   * types, simplices mixed with hypercubes, degenerate simplices and
   * in 1D.
   */
  template <int dim>
  void
  read_vtu(const std::string &file_name, Triangulation<dim> &triangulation);
} // namespace tissuefem::geometry
