#pragma once

#include <tissuefem/materials/energy_material.h>

namespace tissuefem::materials
{
  /// S = 2 mu E + lambda tr(E) I, the isotropic part of St Venant-Kirchhoff
  /// (also of Picinbono's transversely isotropic model).
  template <int dim>
  Tensor<2, dim>
  st_venant_kirchhoff_stress(const double          lambda,
                             const double          mu,
                             const Tensor<2, dim> &E)
  {
    return (2. * mu) * E + (lambda * trace(E)) * unit_symmetric_tensor<dim>();
  }

  /// Adds F_iM F_kQ CC_MJLQ with CC = lambda I x I + 2 mu II to @p A:
  /// lambda F_iJ F_kL + mu (F_iL F_kJ + (F F^T)_ik delta_JL).
  template <int dim>
  void
  add_st_venant_kirchhoff_tangent(const double          lambda,
                                  const double          mu,
                                  const Tensor<2, dim> &F,
                                  Tensor<4, dim>       &A)
  {
    const Tensor<2, dim> B = F * transpose(F);
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int J = 0; J < dim; ++J)
        for (unsigned int k = 0; k < dim; ++k)
          for (unsigned int L = 0; L < dim; ++L)
            A[i][J][k][L]
              += lambda * F[i][J] * F[k][L]
                 + mu * (F[i][L] * F[k][J] + (J == L ? B[i][k] : 0.));
  }

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
      return st_venant_kirchhoff_stress(lambda, mu, E);
    }

    /// F_iM F_kQ CC_MJLQ with CC = lambda I x I + 2 mu II: lambda F_iJ
    /// F_kL + mu (F_iL F_kJ + (F F^T)_ik delta_JL).
    void
    add_material_tangent(const Tensor<2, dim> &F,
                         const Tensor<1, dim> &,
                         Tensor<4, dim> &A) const
    {
      add_st_venant_kirchhoff_tangent(lambda, mu, F, A);
    }

    bool
    has_hand_coded_tangent() const override
    {
      return true;
    }

    bool
    admits_inversion() const override
    {
      return true;
    }

  protected:
    void
    hand_coded_stress_and_tangent(const Tensor<2, dim> &F,
                                  const Tensor<1, dim> &fibre,
                                  Tensor<2, dim>       &P,
                                  Tensor<4, dim>       &A) const override
    {
      quadratic_in_E_stress_and_tangent(*this, F, fibre, P, A);
    }

  private:
    const double lambda;
    const double mu;
  };
} // namespace tissuefem::materials
