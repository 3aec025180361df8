#pragma once

#include <array>

namespace tissuefem::materials
{
  /**
   * A dim x dim matrix of any number type. Energy densities are written on
   * this type, so that the same code evaluates with doubles, with fixed-size
   * Sacado numbers and with deal.II's AD number types.
   */
  template <int dim, typename Number>
  using SmallMatrix = std::array<std::array<Number, dim>, dim>;

  template <int dim, typename Number>
  Number
  determinant(const SmallMatrix<dim, Number> &F)
  {
    if constexpr (dim == 1)
      return F[0][0];
    else if constexpr (dim == 2)
      return F[0][0] * F[1][1] - F[0][1] * F[1][0];
    else
      return F[0][0] * (F[1][1] * F[2][2] - F[1][2] * F[2][1])
             - F[0][1] * (F[1][0] * F[2][2] - F[1][2] * F[2][0])
             + F[0][2] * (F[1][0] * F[2][1] - F[1][1] * F[2][0]);
  }

  /// tr(F^T F) = F_ij F_ij, the first invariant of C = F^T F.
  template <int dim, typename Number>
  Number
  first_invariant(const SmallMatrix<dim, Number> &F)
  {
    Number result = F[0][0] * F[0][0];
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        if (i + j > 0)
          result += F[i][j] * F[i][j];
    return result;
  }

  /// C = F^T F, the right Cauchy-Green tensor.
  template <int dim, typename Number>
  SmallMatrix<dim, Number>
  right_cauchy_green(const SmallMatrix<dim, Number> &F)
  {
    SmallMatrix<dim, Number> C;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        {
          C[i][j] = F[0][i] * F[0][j];
          for (unsigned int k = 1; k < dim; ++k)
            C[i][j] += F[k][i] * F[k][j];
        }
    return C;
  }

  /// E = (C - I) / 2, the Green-Lagrange strain from C.
  template <int dim, typename Number>
  SmallMatrix<dim, Number>
  green_lagrange_from_C(const SmallMatrix<dim, Number> &C)
  {
    SmallMatrix<dim, Number> E;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        E[i][j] = 0.5 * (C[i][j] - (i == j ? 1. : 0.));
    return E;
  }

  template <int dim, typename Number>
  Number
  trace(const SmallMatrix<dim, Number> &M)
  {
    Number result = M[0][0];
    for (unsigned int i = 1; i < dim; ++i)
      result += M[i][i];
    return result;
  }

  /// M : M = M_ij M_ij.
  template <int dim, typename Number>
  Number
  squared_norm(const SmallMatrix<dim, Number> &M)
  {
    return first_invariant<dim, Number>(M);
  }

  /// a . M a for a constant vector a.
  template <int dim, typename Number, typename Vector>
  Number
  quadratic_form(const SmallMatrix<dim, Number> &M, const Vector &a)
  {
    Number result = M[0][0] * (a[0] * a[0]);
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        if (i + j > 0)
          result += M[i][j] * (a[i] * a[j]);
    return result;
  }
} // namespace tissuefem::materials
