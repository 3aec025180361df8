#pragma once

#include <deal.II/fe/fe_values.h>

#include <tissuefem/solid/discretization.h>
#include <tissuefem/solid/formulations/interface.h>

#include <vector>

namespace tissuefem::solid
{
  /**
   * The deformation of the locally owned cells, read from a ghosted
   * displacement @p u: the loops the quantities computed for reports
   * share (quantities.h, self_overlap.h).
   */

  /// x = X + u(X) at vertex @p v of a cell or face (from the vertex dofs).
  template <int dim, typename Iterator>
  Point<dim>
  deformed_vertex(const Iterator    &object,
                  const unsigned int v,
                  const VectorType  &u)
  {
    Point<dim> x = object->vertex(v);
    for (unsigned int c = 0; c < dim; ++c)
      x[c] += u[object->vertex_dof_index(v, c)];
    return x;
  }


  /// Calls @p f(cell, q, F, JxW) at every quadrature point of the locally
  /// owned cells; with a formulation's @p deformation (Solid::deformation()),
  /// F is its effective one, Fbar for the mean or nodal dilatation (the
  /// plain F in cells where Fbar is not defined).
  template <int dim, typename Callback>
  void
  for_each_deformation_gradient(
    const Discretization<dim>            &discretization,
    const VectorType                     &u,
    const Callback                       &f,
    const formulations::Deformation<dim> *deformation = nullptr)
  {
    FEValues<dim>                    fe_values(*discretization.mapping,
                            *discretization.fe,
                            discretization.cell_quadrature,
                            update_gradients | update_JxW_values);
    const FEValuesExtractors::Vector displacement(0);
    std::vector<Tensor<2, dim>> grad_u(discretization.cell_quadrature.size());
    std::vector<Tensor<2, dim>> F(grad_u.size());
    std::vector<double>         JxW(grad_u.size());
    for (const auto &cell : discretization.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[displacement].get_function_gradients(u, grad_u);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              F[q]   = unit_symmetric_tensor<dim>() + grad_u[q];
              JxW[q] = fe_values.JxW(q);
            }
          if (deformation)
            deformation->apply(cell, F, JxW.data(), F.size());
          for (const unsigned int q : fe_values.quadrature_point_indices())
            f(cell, q, F[q], JxW[q]);
        }
  }
} // namespace tissuefem::solid
