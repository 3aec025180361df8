#pragma once

#include <tissuefem/materials/energy_material.h>

namespace tissuefem::materials
{
  /**
   * St Venant-Kirchhoff: Psi = mu E : E + lambda/2 (tr E)^2 with the
   * Green-Lagrange strain E = (F^T F - I)/2. This is Picinbono's non-linear
   * isotropic model (Jeffrey eq 12, whose terms in grad U expand exactly
   * this energy). Frame indifferent, but it softens under strong compression
   * and its energy has a spurious minimum for inverted elements, which is
   * why it does not recover from inversion.
   */
  template <int dim>
  class StVenantKirchhoff : public EnergyMaterial<dim, StVenantKirchhoff<dim>>
  {
  public:
    StVenantKirchhoff(const ElasticConstants &constants,
                      const ParameterHandler &)
        : lambda(constants.lambda)
        , mu(constants.mu)
    {
    }

    static void
    declare_parameters(ParameterHandler &)
    {
    }

    template <typename Number>
    Number
    energy_in_C(const SmallMatrix<dim, Number> &C, const Tensor<1, dim> &) const
    {
      const SmallMatrix<dim, Number> E  = green_lagrange_from_C<dim, Number>(C);
      const Number                   tr = trace<dim, Number>(E);
      return mu * squared_norm<dim, Number>(E) + 0.5 * lambda * tr * tr;
    }

    template <typename Number>
    Number
    energy(const SmallMatrix<dim, Number> &F, const Tensor<1, dim> &a) const
    {
      return energy_in_C(right_cauchy_green<dim, Number>(F), a);
    }

    /// S = dPsi/dE = 2 mu E + lambda tr(E) I in closed form: the explicit
    /// methods' force loop evaluates it at every step (the tests check it
    /// against the energy by finite differences, as every stress).
    Tensor<2, dim>
    second_piola_kirchhoff(const Tensor<2, dim> &E,
                           const Tensor<1, dim> &) const
    {
      return (2. * mu) * E + (lambda * trace(E)) * unit_symmetric_tensor<dim>();
    }

    bool
    admits_inversion() const override
    {
      return true;
    }

  private:
    const double lambda;
    const double mu;
  };
} // namespace tissuefem::materials
