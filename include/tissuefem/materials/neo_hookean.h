#pragma once

#include <tissuefem/materials/energy_material.h>
#include <tissuefem/materials/kinematics.h>

#include <cmath>

namespace tissuefem::materials
{
  /**
   * The volumetric function g(J) of the neo-Hookean family
   *
   *   Psi(F) = mu/2 (F_ij F_ij - d) - mu g(J) + lambda/2 g(J)^2
   *
   * (Teran's lecture notes eq 2.8a with erratum T1 in doc/references.md: the
   * Frobenius norm, minus the dimension d). LogVolume is g = log J; CubicVolume
   * is the cubic Taylor expansion r(J) of log J about J = 1 (eq 2.9a-c), finite
   * for every J, so the model stays defined through inversion.
   */
  struct LogVolume
  {
    static constexpr bool defined_for_inversion = false;

    template <typename Number>
    static Number
    value(const Number &J)
    {
      using std::log;
      return log(J);
    }
    static double
    first_derivative(const double J)
    {
      return 1. / J;
    }
    static double
    second_derivative(const double J)
    {
      return -1. / (J * J);
    }
  };

  struct CubicVolume
  {
    static constexpr bool defined_for_inversion = true;

    /// r(J) = (J-1) - (J-1)^2/2 + (J-1)^3/3, eq 2.9a.
    template <typename Number>
    static Number
    value(const Number &J)
    {
      const Number x = J - 1.;
      return x * (1. + x * (-0.5 + x / 3.));
    }
    /// r'(J) = 1 - (J-1) + (J-1)^2, eq 2.9b.
    static double
    first_derivative(const double J)
    {
      const double x = J - 1.;
      return 1. - x + x * x;
    }
    /// r''(J) = -1 + 2(J-1), eq 2.9c.
    static double
    second_derivative(const double J)
    {
      return -1. + 2. * (J - 1.);
    }
  };

  template <int dim, typename Volume>
  class NeoHookeanFamily
      : public EnergyMaterial<dim, NeoHookeanFamily<dim, Volume>>
  {
  public:
    NeoHookeanFamily(const ElasticConstants &constants,
                     const ParameterHandler &);

    /// Neither model has parameters beyond the elastic constants.
    static void
    declare_parameters(ParameterHandler &)
    {
    }

    /// Psi in the invariants I1 = tr F^T F and J = det F.
    template <typename Number>
    Number
    invariant_energy(const Number &I1, const Number &J) const
    {
      const Number g = Volume::value(J);
      return 0.5 * mu * (I1 - double(dim)) - mu * g + 0.5 * lambda * g * g;
    }

    template <typename Number>
    Number
    energy(const SmallMatrix<dim, Number> &F, const Tensor<1, dim> &) const
    {
      return invariant_energy(first_invariant<dim, Number>(F),
                              determinant<dim, Number>(F));
    }

    /// P = mu F + (lambda g - mu) g' cof F in closed form (as in
    /// hand_coded_stress_and_tangent()), for the force loops of explicit
    /// methods and the lean kernel; checked against the energy by
    /// tissuefem --check-material.
    Tensor<2, dim>
    first_piola_kirchhoff(const Tensor<2, dim> &F, const Tensor<1, dim> &) const
    {
      const double J = determinant(F);
      const double g = Volume::value(J);
      return mu * F
             + ((lambda * g - mu) * Volume::first_derivative(J)) * cofactor(F);
    }

    bool
    has_hand_coded_tangent() const override
    {
      return true;
    }

    bool
    admits_inversion() const override
    {
      return Volume::defined_for_inversion;
    }

    /// lambda/2 g(J)^2.
    VolumetricPart
    volumetric_part(const double J) const override
    {
      return {lambda,
              mu,
              Volume::value(J),
              Volume::first_derivative(J),
              Volume::second_derivative(J)};
    }

  protected:
    /**
     * P = mu F + (lambda g - mu) g' cof F and
     * dP_ij/dF_kl = mu d_ik d_jl + (lambda g'^2 + (lambda g - mu) g'')
     *               cof_ij cof_kl + (lambda g - mu) g' dcof_ij/dF_kl,
     * with cof F = dJ/dF (problem session eqs 13 and 20, in d dimensions).
     */
    void
    hand_coded_stress_and_tangent(const Tensor<2, dim> &F,
                                  const Tensor<1, dim> &,
                                  Tensor<2, dim> &P,
                                  Tensor<4, dim> &A) const override;

  private:
    const double lambda;
    const double mu;
  };

  template <int dim>
  using NeoHookean = NeoHookeanFamily<dim, LogVolume>;

  template <int dim>
  using RobustNeoHookean = NeoHookeanFamily<dim, CubicVolume>;
} // namespace tissuefem::materials
