#pragma once

#include <deal.II/base/tensor.h>

namespace tissuefem::materials
{
  using namespace dealii;

  /// The cofactor matrix cof F = dJ/dF = J F^{-T}, defined for singular F
  /// too (which inversion-robust models need).
  template <int dim>
  Tensor<2, dim>
  cofactor(const Tensor<2, dim> &F)
  {
    Tensor<2, dim> C;
    if constexpr (dim == 1)
      C[0][0] = 1.;
    else if constexpr (dim == 2)
      {
        C[0][0] = F[1][1];
        C[0][1] = -F[1][0];
        C[1][0] = -F[0][1];
        C[1][1] = F[0][0];
      }
    else
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          {
            const unsigned int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
            const unsigned int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            C[i][j] = F[i1][j1] * F[i2][j2] - F[i1][j2] * F[i2][j1];
          }
    return C;
  }

  /**
   * Adds @p factor * d(cof F)_ij / dF_kl to A_ijkl. The derivative is zero
   * in 1D, eps_ik eps_jl in 2D and eps_ikn eps_jlq F_nq in 3D (from
   * cof_ij = 1/2 eps_imn eps_jpq F_mp F_nq).
   */
  template <int dim>
  void
  add_cofactor_derivative(const Tensor<2, dim> &F,
                          const double          factor,
                          Tensor<4, dim>       &A)
  {
    if constexpr (dim == 2)
      {
        // eps_ik eps_jl is non-zero for i != k and j != l only.
        for (unsigned int i = 0; i < 2; ++i)
          for (unsigned int j = 0; j < 2; ++j)
            A[i][j][1 - i][1 - j] += factor * (i == j ? 1. : -1.);
      }
    else if constexpr (dim == 3)
      {
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int k = 0; k < 3; ++k)
            if (i != k)
              {
                const unsigned int n = 3 - i - k;
                // eps_ikn = +1 for cyclic (i, k, n), -1 otherwise.
                const double eps_ikn = ((k + 3 - i) % 3 == 1) ? 1. : -1.;
                for (unsigned int j = 0; j < 3; ++j)
                  for (unsigned int l = 0; l < 3; ++l)
                    if (j != l)
                      {
                        const unsigned int q = 3 - j - l;
                        const double       eps_jlq
                          = ((l + 3 - j) % 3 == 1) ? 1. : -1.;
                        A[i][j][k][l] += factor * eps_ikn * eps_jlq * F[n][q];
                      }
              }
      }
  }
} // namespace tissuefem::materials
