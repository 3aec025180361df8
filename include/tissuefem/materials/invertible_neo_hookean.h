#pragma once

#include <tissuefem/materials/interface.h>

#include <array>

namespace tissuefem::materials
{
  /**
   * Neo-Hookean made invertible in the manner of Irving, Teran and Fedkiw
   * (2004): the energy of an isotropic material depends on F only through
   * its signed singular values sigma (F = U diag(sigma) V^T with U, V
   * rotations, so an inverted F has one negative sigma), and there the
   * log-J neo-Hookean energy (Teran eq 2.8a),
   *
   *   Psi = mu/2 (sum sigma_i^2 - d) - mu L + lambda/2 L^2,
   *   L = sum_i l(sigma_i),  l = log,
   *
   * is extended below a compression limit c: l(s) = log c + (s - c)/c -
   * (s - c)^2/(2 c^2) for s < c, its second-order Taylor expansion, so Psi
   * is twice differentiable, finite for every F, and l' > 0 everywhere
   * below 2c: a compressed, flattened, collapsed (F = 0) or inverted
   * element pushes back towards its rest shape, which the r(J) model of
   * Teran eq 2.9 does not do at F = 0 (there its stress vanishes).
   *
   * Stress P = U diag(dPsi/dsigma) V^T; tangent from the diagonalized
   * derivatives (Teran, Sifakis, Irving and Fedkiw 2005, eq 6-8): the
   * Hessian in sigma and, for each pair i != j, the 2 x 2 block with
   * entries (dPsi_i - dPsi_j)/(sigma_i - sigma_j) +- (dPsi_i +
   * dPsi_j)/(sigma_i + sigma_j), halved, evaluated without cancellation
   * when singular values coincide.
   */
  template <int dim>
  class InvertibleNeoHookean : public Interface<dim>
  {
  public:
    InvertibleNeoHookean(const ElasticConstants &constants,
                         const ParameterHandler &prm);

    static void
    declare_parameters(ParameterHandler &prm);

    double
    energy_density(const Tensor<2, dim> &F,
                   const Tensor<1, dim> &fibre) const override;

    Tensor<2, dim>
    stress(const Tensor<2, dim> &F, const Tensor<1, dim> &fibre) const override;

    void
    stress_and_tangent(const Tensor<2, dim> &F,
                       const Tensor<1, dim> &fibre,
                       Tensor<2, dim>       &P,
                       Tensor<4, dim>       &A,
                       const TangentMethod   method) const override;

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

    /// F = U diag(sigma) V^T with det U = det V = 1; sigma_1 >= ... >=
    /// |sigma_d|, the last negative where det F < 0.
    static void
    signed_svd(const Tensor<2, dim>    &F,
               Tensor<2, dim>          &U,
               std::array<double, dim> &sigma,
               Tensor<2, dim>          &V);

  private:
    double lambda, mu, limit;

    /// l(s), l'(s), l''(s).
    std::array<double, 3>
    extended_log(const double s) const;

    /// dPsi/dsigma_i and (optionally) d2Psi/dsigma_i dsigma_j.
    double
    diagonal_derivatives(const std::array<double, dim> &sigma,
                         std::array<double, dim>       &gradient,
                         double (*hessian)[dim]) const;
  };
} // namespace tissuefem::materials
