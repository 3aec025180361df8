#pragma once

#include <tissuefem/solid/formulations/interface.h>

namespace tissuefem::solid::formulations
{
  /**
   * The displacement element: the first Piola-Kirchhoff stress P(F) and
   * its tangent at every quadrature point, from the deformation gradient
   * there (problem session eqs 17-19). Any element; on linear simplices the
   * lean kernel serves it whole.
   */
  template <int dim>
  class Displacement : public Interface<dim>
  {
  public:
    void
    check(const Discretization<dim>         &discretization,
          const materials::MaterialSet<dim> &materials) const override;

    typename Interface<dim>::LeanKernel
    lean_kernel() const override
    {
      return Interface<dim>::LeanKernel::all;
    }

    bool
    cell_terms(const Context<dim> &context,
               CellTerms<dim>     &cell) const override;
  };
} // namespace tissuefem::solid::formulations
