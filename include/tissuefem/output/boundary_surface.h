#pragma once

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/base/parallel.h>

#include <cstdint>
#include <vector>

namespace tissuefem::output
{
  using namespace dealii;

  /**
   * What a picture of the body needs: the mesh's outer surface as
   * triangles over the mesh's vertices (in 3D the boundary faces,
   * quadrilaterals split along a diagonal; in 2D every cell, the body being
   * flat), and values gathered at those vertices from every process.
   * Built from the whole mesh, which every process holds
   * (parallel::shared::Triangulation); only the vertices matter, so a
   * higher-degree element is drawn with straight edges.
   */
  template <int dim>
  class BoundarySurface
  {
  public:
    /// The surface of @p triangulation's active cells (empty in 1D).
    explicit BoundarySurface(const Triangulation<dim> &triangulation);

    /// The triangulation's indices of the surface vertices; surface vertex
    /// s is vertices[s].
    std::vector<unsigned int> vertices;
    /// Three surface-vertex indices per triangle, oriented outwards in 3D.
    std::vector<std::uint32_t> triangles;
    /// Reference positions, 3 per surface vertex (z = 0 in 2D).
    std::vector<float> positions;

    /**
     * The displacement at each surface vertex (3 per vertex, z = 0 in 2D)
     * from @p u (ghosted: the entries of this process's cells), and the
     * average at each surface vertex of @p cell_values (one Vector per
     * field, indexed by active cell, given on this process's cells) over
     * the cells around it. Collective; every process gets the result.
     */
    void
    gather(const DoFHandler<dim>            &dof_handler,
           const VectorType                 &u,
           const std::vector<Vector<float>> &cell_values,
           std::vector<float>               &displacement,
           std::vector<std::vector<float>>  &vertex_values) const;

  private:
    /// Triangulation vertex -> surface vertex (or none).
    std::vector<unsigned int> surface_index;
  };
} // namespace tissuefem::output
