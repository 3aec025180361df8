#pragma once

#include <tissuefem/materials/energy_material.h>
#include <tissuefem/materials/st_venant_kirchhoff.h>

namespace tissuefem::materials
{
  /**
   * Picinbono's transversely isotropic St Venant-Kirchhoff material (Jeffrey
   * eqs 16-18 and 24):
   *
   *   Psi = mu E : E + lambda/2 (tr E)^2 + (Delta lambda / 2 + Delta mu)
   *         (a . E a)^2,
   *
   * with (lambda, mu) the Lame pair across the fibre (from the Materials
   * subsection) and Delta lambda = lambda^L - lambda, Delta mu = mu^L - mu
   * from the pair (E^L, nu^L) along the unit fibre direction a (erratum J1 in
   * doc/references.md; item 1 on the names lambda^L, lambda^T). Shearing and
   * cross-stretching terms are neglected, as in the report.
   */
  template <int dim>
  class TransverselyIsotropic
      : public EnergyMaterial<dim, TransverselyIsotropic<dim>>
  {
  public:
    TransverselyIsotropic(const ElasticConstants &constants,
                          const ParameterHandler &prm);

    static void
    declare_parameters(ParameterHandler &prm);

    template <typename Number>
    Number
    energy_in_C(const SmallMatrix<dim, Number> &C,
                const Tensor<1, dim>           &a) const
    {
      const SmallMatrix<dim, Number> E  = green_lagrange_from_C<dim, Number>(C);
      const Number                   tr = trace<dim, Number>(E);
      const Number                   Ea = quadratic_form<dim, Number>(E, a);
      return mu * squared_norm<dim, Number>(E) + 0.5 * lambda * tr * tr
             + fibre_coefficient * Ea * Ea;
    }

    template <typename Number>
    Number
    energy(const SmallMatrix<dim, Number> &F, const Tensor<1, dim> &a) const
    {
      return energy_in_C(right_cauchy_green<dim, Number>(F), a);
    }

    /// S = dPsi/dE = 2 mu E + lambda tr(E) I + 2 k (a.Ea) a x a, k the
    /// fibre coefficient, in closed form for the explicit methods' force
    /// loop (checked against the energy by finite differences).
    Tensor<2, dim>
    second_piola_kirchhoff(const Tensor<2, dim> &E,
                           const Tensor<1, dim> &a) const
    {
      return st_venant_kirchhoff_stress(lambda, mu, E)
             + (2. * fibre_coefficient * (a * (E * a))) * outer_product(a, a);
    }

    /// F_iM F_kQ CC_MJLQ with CC = lambda I x I + 2 mu II + 2 k a x a x a
    /// x a: the isotropic terms of St Venant-Kirchhoff plus 2 k (F a)_i
    /// a_J (F a)_k a_L.
    void
    add_material_tangent(const Tensor<2, dim> &F,
                         const Tensor<1, dim> &a,
                         Tensor<4, dim>       &A) const
    {
      add_st_venant_kirchhoff_tangent(lambda, mu, F, A);
      const Tensor<1, dim> Fa = F * a;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int J = 0; J < dim; ++J)
          for (unsigned int k = 0; k < dim; ++k)
            for (unsigned int L = 0; L < dim; ++L)
              A[i][J][k][L]
                += 2. * fibre_coefficient * Fa[i] * a[J] * Fa[k] * a[L];
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

    bool
    uses_fibres() const override
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
    double lambda;
    double mu;
    /// Delta lambda / 2 + Delta mu (stress units).
    double fibre_coefficient;
  };
} // namespace tissuefem::materials
