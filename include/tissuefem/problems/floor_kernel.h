#pragma once

#include <deal.II/lac/sparsity_pattern.h>

#include <tissuefem/materials/material_set.h>
#include <tissuefem/solid/cell_cache.h>
#include <tissuefem/solid/discretization.h>
#include <tissuefem/solid/fibre_field.h>

#include <vector>

namespace tissuefem::problems
{
  /**
   * The floor against which assembly is measured: the same element
   * arithmetic as solid::Solid (F from the displacement, the material's P
   * and dP/dF by the chosen tangent method, the element residual and
   * stiffness) on shape gradients computed beforehand, adding into plain
   * arrays through a cached map from element entries to matrix entries: no
   * FEValues, no constraints, no distributed objects, no threads. Internal
   * forces only (no loads, no mass), one process's cells.
   */
  template <int dim>
  class FloorKernel
  {
  public:
    FloorKernel(const solid::Discretization<dim>  &discretization,
                const materials::MaterialSet<dim> &materials);

    /// One pass over the cells: f_int(u) into residual(), and with
    /// @p jacobian K(u) into the matrix values.
    void
    assemble(const Vector<double> &u, const bool jacobian);

    const Vector<double> &
    residual() const
    {
      return residual_values;
    }

    const std::vector<double> &
    matrix_values() const
    {
      return values;
    }

    /// The entry index of (row, column) in matrix_values().
    std::size_t
    entry(const types::global_dof_index row,
          const types::global_dof_index column) const
    {
      return sparsity(row, column);
    }

  private:
    const materials::MaterialSet<dim> &materials;
    solid::FibreField<dim>             fibres;
    solid::CellCache<dim>              cache;
    SparsityPattern                    sparsity;
    /// positions[c * n * n + i * n + j]: entry of element entry (i, j).
    std::vector<std::size_t> positions;
    std::vector<double>      values;
    Vector<double>           residual_values;
  };
} // namespace tissuefem::problems
