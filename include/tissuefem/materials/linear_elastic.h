#pragma once

#include <tissuefem/materials/energy_material.h>

namespace tissuefem::materials
{
  /**
   * Small-strain isotropic linear elasticity (Teran's lecture notes,
   * 'Elasticity and Constitutive Modeling'; Jeffrey eq 4):
   *
   *   Psi = mu eps : eps + lambda/2 (tr eps)^2,  eps = (F + F^T)/2 - I.
   *
   * Not rotation invariant: a rigid rotation produces strain and stress, so
   * the model is only valid for small rotations. Cheap and linear; the
   * reference against which the nonlinear models are compared.
   */
  template <int dim>
  class LinearElastic : public EnergyMaterial<dim, LinearElastic<dim>>
  {
  public:
    LinearElastic(const ElasticConstants &constants, const ParameterHandler &)
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
    energy(const SmallMatrix<dim, Number> &F, const Tensor<1, dim> &) const
    {
      SmallMatrix<dim, Number> eps;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          eps[i][j] = 0.5 * (F[i][j] + F[j][i]) - (i == j ? 1. : 0.);
      const Number tr = trace<dim, Number>(eps);
      return mu * squared_norm<dim, Number>(eps) + 0.5 * lambda * tr * tr;
    }

    bool
    admits_inversion() const override
    {
      return true;
    }

    bool
    frame_indifferent() const override
    {
      return false;
    }

  private:
    const double lambda;
    const double mu;
  };
} // namespace tissuefem::materials
