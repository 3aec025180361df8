#include <deal.II/fe/fe_values.h>

#include <tissuefem/solid/fibre_field.h>

namespace tissuefem::solid
{
  template <int dim>
  void
  FibreField<dim>::build(const Discretization<dim>         &discretization,
                         const materials::MaterialSet<dim> &materials,
                         const bool                         per_cell)
  {
    directions.clear();
    if (!materials.any_uses_fibres())
      return;
    const auto &dof_handler = discretization.dof_handler;
    n_q                     = discretization.cell_quadrature.size();
    FEValues<dim> fe_values(*discretization.mapping,
                            *discretization.fe,
                            discretization.cell_quadrature,
                            update_quadrature_points);
    directions.assign(dof_handler.get_triangulation().n_active_cells() * n_q,
                      unused);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          const unsigned int first = cell->active_cell_index() * n_q;
          Tensor<1, dim>     mean;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              directions[first + q]
                = materials.fibre_direction(fe_values.quadrature_point(q));
              mean += directions[first + q];
            }
          // The edge-length element has one fibre per element; use the same
          // (normalized mean) direction at every quadrature point so that
          // energies and stresses reported afterwards belong to the problem
          // solved.
          if (per_cell && mean.norm() > 0)
            for (unsigned int q = 0; q < n_q; ++q)
              directions[first + q] = mean / mean.norm();
        }
  }


  template <int dim>
  std::vector<Vector<float>>
  FibreField<dim>::cell_averages(const unsigned int n_active_cells) const
  {
    std::vector<Vector<float>> result;
    if (directions.empty())
      return result;
    result.assign(dim, Vector<float>(n_active_cells));
    for (unsigned int c = 0; c < n_active_cells; ++c)
      {
        Tensor<1, dim> mean;
        for (unsigned int q = 0; q < n_q; ++q)
          mean += directions[c * n_q + q];
        mean /= std::max(mean.norm(), 1e-300);
        for (unsigned int d = 0; d < dim; ++d)
          result[d][c] = mean[d];
      }
    return result;
  }

  template class FibreField<1>;
  template class FibreField<2>;
  template class FibreField<3>;
} // namespace tissuefem::solid
