#include <deal.II/base/memory_consumption.h>
#include <deal.II/fe/fe_values.h>

#include <tissuefem/solid/cell_cache.h>

namespace tissuefem::solid
{
  template <int dim>
  void
  CellCache<dim>::build(const Discretization<dim> &discretization,
                        const bool                 positions)
  {
    const auto &fe     = *discretization.fe;
    const auto &scalar = fe.base_element(0);
    n_q                = discretization.cell_quadrature.size();
    n_scalar           = scalar.n_dofs_per_cell();
    n_dofs             = fe.n_dofs_per_cell();
    n_compon           = fe.n_components();
    local_index.assign(n_scalar * n_compon, 0);
    for (unsigned int i = 0; i < n_dofs; ++i)
      {
        const auto [component, k]             = fe.system_to_component_index(i);
        local_index[k * n_compon + component] = i;
      }

    FEValues<dim> fe_values(*discretization.mapping,
                            scalar,
                            discretization.cell_quadrature,
                            update_values | update_gradients | update_JxW_values
                              | (positions ? update_quadrature_points
                                           : update_default));
    owned_cells.clear();
    for (const auto &cell : discretization.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        owned_cells.push_back(cell);
    const std::size_t n_cells = owned_cells.size();
    // Linear simplices under their affine mapping (MappingFE of P1): the
    // gradients are the same at every point, one set per cell (on SOFA's
    // large beam, at the default 6 points, 480 bytes per cell less).
    const bool constant = discretization.simplex && scalar.degree == 1;
    q_stride            = constant ? 0 : n_scalar;
    cell_stride         = constant ? n_scalar : n_q * n_scalar;
    dof_indices.resize(n_cells * n_dofs);
    jxw.resize(n_cells * n_q);
    gradients.resize(n_cells * cell_stride);
    points.resize(positions ? n_cells * n_q : 0);
    values.resize(n_q * n_scalar);

    std::vector<types::global_dof_index> dofs(n_dofs);
    for (std::size_t c = 0; c < n_cells; ++c)
      {
        const auto &cell = owned_cells[c];
        // A Triangulation iterator: FEValues of the scalar element need
        // only the geometry.
        fe_values.reinit(
          static_cast<typename Triangulation<dim>::cell_iterator>(cell));
        cell->get_dof_indices(dofs);
        std::copy(dofs.begin(), dofs.end(), dof_indices.begin() + c * n_dofs);
        for (unsigned int q = 0; q < n_q; ++q)
          {
            jxw[c * n_q + q] = fe_values.JxW(q);
            if (positions)
              points[c * n_q + q] = fe_values.quadrature_point(q);
            for (unsigned int k = 0; k < n_scalar; ++k)
              {
                if (q == 0 || !constant)
                  gradients[c * cell_stride + q * q_stride + k]
                    = fe_values.shape_grad(k, q);
                if (c == 0)
                  values[q * n_scalar + k] = fe_values.shape_value(k, q);
              }
          }
      }
  }


  template <int dim>
  std::size_t
  CellCache<dim>::memory_consumption() const
  {
    return MemoryConsumption::memory_consumption(local_index)
           + MemoryConsumption::memory_consumption(values)
           + owned_cells.capacity() * sizeof(CellIterator)
           + MemoryConsumption::memory_consumption(dof_indices)
           + MemoryConsumption::memory_consumption(jxw)
           + MemoryConsumption::memory_consumption(gradients)
           + MemoryConsumption::memory_consumption(points);
  }


  template class CellCache<1>;
  template class CellCache<2>;
  template class CellCache<3>;
} // namespace tissuefem::solid
