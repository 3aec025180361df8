#pragma once

#include <tissuefem/materials/neo_hookean.h>

#include <cmath>

namespace tissuefem::materials
{
  /**
   * Fibre-reinforced inversion-robust neo-Hookean (lecture notes,
   * 'Elasticity and Constitutive Modeling'):
   *
   *   Psi(F) = Psi_iso(F) + Psi_fibre(I4),  I4 = a . F^T F a = |F a|^2,
   *
   * with Psi_iso the robust neo-Hookean energy (eq 2.9) and a the unit
   * reference fibre direction. I4 >= 0 is the squared fibre stretch and is
   * defined for every F, so the model stays defined through inversion. Fibre
   * laws (k1 in stress units, k2 dimensionless):
   * - quadratic:   Psi_fibre = k1/4 (I4 - 1)^2, resists stretch and
   *   compression; adds 2 k1 to the small-strain modulus along a;
   * - exponential: Psi_fibre = k1/(2 k2) (exp(k2 (I4 - 1)^2) - 1) for
   *   I4 > 1 and 0 otherwise (collagen-like: stiffening in tension, slack in
   *   compression; the tangent jumps at I4 = 1).
   */
  template <int dim>
  class FibreReinforced : public EnergyMaterial<dim, FibreReinforced<dim>>
  {
  public:
    FibreReinforced(const ElasticConstants &constants,
                    const ParameterHandler &prm);

    static void
    declare_parameters(ParameterHandler &prm);

    template <typename Number>
    Number
    energy(const SmallMatrix<dim, Number> &F, const Tensor<1, dim> &a) const
    {
      using std::exp;
      const Number I4
        = quadratic_form<dim, Number>(right_cauchy_green<dim, Number>(F), a);
      const Number stretch = I4 - 1.;
      Number       fibre   = 0. * stretch;
      if (exponential_law)
        {
          if (stretch > 0.)
            fibre = k1 / (2. * k2) * (exp(k2 * stretch * stretch) - 1.);
        }
      else
        fibre = 0.25 * k1 * stretch * stretch;
      return matrix.energy(F, a) + fibre;
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

  private:
    RobustNeoHookean<dim> matrix;
    bool                  exponential_law;
    double                k1, k2;
  };
} // namespace tissuefem::materials
