#pragma once

#include <tissuefem/materials/energy_material.h>

#include <cmath>

namespace tissuefem::materials
{
  /**
   * Corotational linear elasticity, the model SOFA and Vega use for speed:
   * the small-strain energy measured in the element's rotated frame,
   *
   *   Psi = mu |F - R|^2 + lambda/2 (tr(R^T F) - d)^2,
   *
   * with R the rotation of the polar decomposition F = R S. Here R depends
   * on F and is differentiated exactly (the "exact" corotational stress and
   * tangent, including dR/dF terms that simulators often drop). In 2D R has
   * a closed form; in 3D it is the limit of Higham's scaled Newton iteration
   * X <- (g X + X^{-T}/g)/2, run to round-off with AD numbers so that its
   * derivatives converge with it. Undefined at det F = 0.
   */
  template <int dim>
  class Corotational : public EnergyMaterial<dim, Corotational<dim>>
  {
  public:
    Corotational(const ElasticConstants &constants, const ParameterHandler &)
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
      const SmallMatrix<dim, Number> R        = rotation(F);
      Number                         distance = 0. * F[0][0];
      Number                         tr_RtF   = 0. * F[0][0];
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          {
            const Number d = F[i][j] - R[i][j];
            distance += d * d;
            tr_RtF += R[i][j] * F[i][j];
          }
      const Number volumetric = tr_RtF - double(dim);
      return mu * distance + 0.5 * lambda * volumetric * volumetric;
    }

    /**
     * P = dPsi/dF = 2 mu (F - R) + lambda (tr(R^T F) - d) R in closed form,
     * for the explicit methods' force loop (the tangent stays AD): with F =
     * R S, the terms of dR vanish in the gradient, since R^T dR is skew and
     * S - I and the identity are symmetric (McAdams et al. 2011 give the
     * same stress). R is the polar rotation in double precision, a few
     * iterations instead of AD through all of them; tissuefem
     * --check-material checks it against the energy.
     */
    Tensor<2, dim>
    first_piola_kirchhoff(const Tensor<2, dim> &F, const Tensor<1, dim> &) const
    {
      SmallMatrix<dim, double> matrix;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          matrix[i][j] = F[i][j];
      const SmallMatrix<dim, double> R       = rotation(matrix);
      double                         trace_S = 0;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          trace_S += R[i][j] * F[i][j];
      Tensor<2, dim> P;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          P[i][j] = 2. * mu * (F[i][j] - R[i][j])
                    + lambda * (trace_S - double(dim)) * R[i][j];
      return P;
    }

    bool
    admits_inversion() const override
    {
      return false;
    }

  private:
    const double lambda;
    const double mu;

    template <typename Number>
    static SmallMatrix<dim, Number>
    rotation(const SmallMatrix<dim, Number> &F)
    {
      using std::sqrt;
      SmallMatrix<dim, Number> R;
      if constexpr (dim == 1)
        R[0][0] = (F[0][0] > 0. ? 1. : -1.) + 0. * F[0][0];
      else if constexpr (dim == 2)
        {
          // The rotation closest to F: angle of (F00 + F11, F10 - F01).
          const Number c = F[0][0] + F[1][1], s = F[1][0] - F[0][1];
          const Number r = sqrt(c * c + s * s);
          R[0][0]        = c / r;
          R[0][1]        = -s / r;
          R[1][0]        = s / r;
          R[1][1]        = c / r;
        }
      else
        {
          R = F;
          for (unsigned int iteration = 0; iteration < 30; ++iteration)
            {
              const Number J = determinant<dim, Number>(R);
              // X^{-T} = cof X / det X.
              SmallMatrix<dim, Number> inverse_transpose;
              for (unsigned int i = 0; i < 3; ++i)
                for (unsigned int j = 0; j < 3; ++j)
                  {
                    const unsigned int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
                    const unsigned int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
                    inverse_transpose[i][j]
                      = (R[i1][j1] * R[i2][j2] - R[i1][j2] * R[i2][j1]) / J;
                  }
              const Number g
                = sqrt(sqrt(first_invariant<dim, Number>(inverse_transpose)
                            / first_invariant<dim, Number>(R)));
              double change = 0;
              for (unsigned int i = 0; i < 3; ++i)
                for (unsigned int j = 0; j < 3; ++j)
                  {
                    const Number next
                      = 0.5 * (g * R[i][j] + inverse_transpose[i][j] / g);
                    change
                      = std::max(change,
                                 std::abs(value_of(next) - value_of(R[i][j])));
                    R[i][j] = next;
                  }
              // Two more sweeps after the values converge let the
              // derivatives (which converge with them) settle too; plain
              // numbers stop at once.
              if (change < 1e-15
                  && (std::is_arithmetic_v<Number> || iteration > 2))
                break;
            }
        }
      return R;
    }

    /// The plain value of a (possibly nested) AD number.
    template <typename Number>
    static double
    value_of(const Number &x)
    {
      if constexpr (std::is_arithmetic_v<Number>)
        return x;
      else
        return value_of(x.val());
    }
  };
} // namespace tissuefem::materials
