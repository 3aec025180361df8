#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/materials/interface.h>

#include <vector>

namespace tissuefem::solid
{
  using namespace dealii;

  /**
   * Adds the forces and stiffness of Jeffrey's edge-length element (eqs
   * 19-31) for one linear simplex to the element residual and (if not
   * null) the element matrix (upper triangle, i <= j). @p vertices are the
   * reference positions of its dim + 1 nodes, @p gradients the reference
   * gradients of its barycentric coordinates, @p volume its reference
   * volume, @p displacement[k][c] the displacement of node k, and
   * @p local_index[k * dim + c] the element's dof of node k, component c.
   */
  template <int dim>
  void
  add_edge_length_element(const std::vector<Point<dim>>     &vertices,
                          const std::vector<Tensor<1, dim>> &gradients,
                          const double                       volume,
                          const std::vector<Tensor<1, dim>> &displacement,
                          const std::vector<unsigned int>   &local_index,
                          const materials::Interface<dim>   &material,
                          const Tensor<1, dim>              &fibre,
                          Vector<double>                    &cell_rhs,
                          FullMatrix<double>                *cell_matrix);
} // namespace tissuefem::solid
