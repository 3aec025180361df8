#pragma once

#include <deal.II/base/tensor.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/materials/material_set.h>
#include <tissuefem/solid/discretization.h>

#include <vector>

namespace tissuefem::solid
{
  /**
   * The unit reference fibre direction at every quadrature point of the
   * locally owned cells, from the 'Materials/Fibre direction' expression.
   * Since the field is an expression of the reference position, it is
   * evaluated anew on every mesh (exact, where interpolating stored values
   * would smear them). Empty when no material uses fibres.
   */
  template <int dim>
  class FibreField
  {
  public:
    /// Evaluates the field on the current mesh of @p discretization; with
    /// @p per_cell (a formulation with one fibre per element: the
    /// edge-length element) the normalized cell mean at every point.
    void
    build(const Discretization<dim>         &discretization,
          const materials::MaterialSet<dim> &materials,
          const bool                         per_cell = false);

    /// The direction at quadrature point @p q of the cell with active
    /// index @p cell_index (any unit vector if no material uses fibres).
    const Tensor<1, dim> &
    at(const unsigned int cell_index, const unsigned int q) const
    {
      if (directions.empty())
        return unused;
      return directions[cell_index * n_q + q];
    }

    bool
    empty() const
    {
      return directions.empty();
    }

    /// The cell averages, normalized, one vector per component.
    std::vector<Vector<float>>
    cell_averages(const unsigned int n_active_cells) const;

  private:
    unsigned int                n_q = 0;
    std::vector<Tensor<1, dim>> directions;
    Tensor<1, dim>              unused = unit_vector();

    static Tensor<1, dim>
    unit_vector()
    {
      Tensor<1, dim> e;
      e[0] = 1.;
      return e;
    }
  };
} // namespace tissuefem::solid
