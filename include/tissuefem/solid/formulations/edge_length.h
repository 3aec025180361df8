#pragma once

#include <tissuefem/solid/formulations/interface.h>

namespace tissuefem::solid::formulations
{
  /**
   * Jeffrey's edge-length element (eqs 19-31; solid/edge_length_element.h):
   * the energy of a linear simplex written through its squared edge
   * lengths, for models written in C = F^T F (St Venant-Kirchhoff and its
   * transversely isotropic variant), with one fibre direction per element
   * (the normalized cell mean).
   */
  template <int dim>
  class EdgeLength : public Interface<dim>
  {
  public:
    void
    check(const Discretization<dim>         &discretization,
          const materials::MaterialSet<dim> &materials) const override;

    bool
    fibre_per_cell() const override
    {
      return true;
    }

    std::unique_ptr<Scratch>
    make_scratch(const Context<dim> &context) const override;

    /// Checks the cell's inversion only: its terms are whole-element rows.
    bool
    cell_terms(const Context<dim> &context,
               CellTerms<dim>     &cell) const override;

    void
    add_cell_rows(const Context<dim> &context,
                  CellTerms<dim>     &cell) const override;
  };
} // namespace tissuefem::solid::formulations
