#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>

#include <tissuefem/solid/discretization.h>

#include <vector>

namespace tissuefem::solid
{
  /**
   * What assembly needs of the geometry of each locally owned cell,
   * computed once per mesh: the global indices of its degrees of freedom,
   * JxW at each quadrature point, and the reference gradients of the
   * scalar shape functions (the vector element is dim copies of one scalar
   * element, so dim times fewer numbers than FEValues keeps). Assembly then
   * does only the element arithmetic: for P1 tetrahedra the gradients are
   * constant and the per-cell cost drops to that of a hand-written kernel.
   * Memory per cell: 8 (n_q (1 + dim n_scalar) + n_dofs) bytes, 8 (n_q +
   * dim n_scalar + n_dofs) on linear simplices.
   */
  template <int dim>
  class CellCache
  {
  public:
    using CellIterator = typename DoFHandler<dim>::active_cell_iterator;

    /// Rebuilds the cache for the current mesh; with @p positions, also
    /// the quadrature points (for body forces given as expressions).
    void
    build(const Discretization<dim> &discretization, const bool positions);

    /// The locally owned cells, in the order of the cache.
    const std::vector<CellIterator> &
    cells() const
    {
      return owned_cells;
    }

    unsigned int n_q      = 0; ///< quadrature points per cell
    unsigned int n_scalar = 0; ///< scalar shape functions per cell
    unsigned int n_dofs   = 0; ///< n_scalar * components
    unsigned int n_compon = 0; ///< components of the element
    /// local_index[k * n_compon + c]: the element's dof of scalar node k
    /// and component c.
    std::vector<unsigned int> local_index;
    /// values[q * n_scalar + k]: the scalar shape value (same on every cell).
    std::vector<double> values;

    /// The dofs of cached cell @p c (global indices, element order).
    const types::global_dof_index *
    dofs(const unsigned int c) const
    {
      return &dof_indices[c * n_dofs];
    }
    const double *
    JxW(const unsigned int c) const
    {
      return &jxw[c * n_q];
    }
    /// gradient(c, q, k): grad of scalar shape function k at point q.
    const Tensor<1, dim> &
    gradient(const unsigned int c,
             const unsigned int q,
             const unsigned int k) const
    {
      return gradients[c * cell_stride + q * q_stride + k];
    }
    const Point<dim> &
    point(const unsigned int c, const unsigned int q) const
    {
      return points[c * n_q + q];
    }

    /// Bytes held (the vectors' capacities).
    std::size_t
    memory_consumption() const;

  private:
    std::vector<CellIterator>            owned_cells;
    std::vector<types::global_dof_index> dof_indices;
    std::vector<double>                  jxw;
    /// gradient(c, q, k) at c * cell_stride + q * q_stride + k: q_stride
    /// is 0 where the gradients are constant on each cell (linear
    /// simplices), which keeps one set per cell.
    std::vector<Tensor<1, dim>> gradients;
    unsigned int                cell_stride = 0, q_stride = 0;
    std::vector<Point<dim>>     points;
  };
} // namespace tissuefem::solid
