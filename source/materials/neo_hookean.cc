#include <tissuefem/materials/neo_hookean.h>

namespace tissuefem::materials
{
  namespace
  {
    /// The Levi-Civita symbol in three dimensions.
    int
    levi_civita(const unsigned int i, const unsigned int j, const unsigned int k)
    {
      return static_cast<int>((j + 3 - i) % 3 == 1 ? 1 : -1) *
             ((i != j && j != k && i != k) ? 1 : 0);
    }

    /// The cofactor matrix cof F = J F^{-T}, defined for singular F too.
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

    /// d(cof F)_ij / dF_kl: zero in 1D, eps_ik eps_jl in 2D and
    /// eps_ikn eps_jlq F_nq in 3D.
    template <int dim>
    double
    cofactor_derivative(const Tensor<2, dim> &F,
                        const unsigned int    i,
                        const unsigned int    j,
                        const unsigned int    k,
                        const unsigned int    l)
    {
      if constexpr (dim == 1)
        return 0.;
      else if constexpr (dim == 2)
        {
          const auto eps = [](unsigned int a, unsigned int b) {
            return a == b ? 0. : (a < b ? 1. : -1.);
          };
          return eps(i, k) * eps(j, l);
        }
      else
        {
          if (i == k || j == l)
            return 0.;
          const unsigned int n = 3 - i - k, q = 3 - j - l;
          return levi_civita(i, k, n) * levi_civita(j, l, q) * F[n][q];
        }
    }
  } // namespace


  template <int dim, typename Volume>
  NeoHookeanFamily<dim, Volume>::NeoHookeanFamily(
    const ElasticConstants &constants,
    const ParameterHandler &)
    : lambda(constants.lambda)
    , mu(constants.mu)
  {}


  template <int dim, typename Volume>
  void
  NeoHookeanFamily<dim, Volume>::hand_coded_stress_and_tangent(
    const Tensor<2, dim> &F,
    Tensor<2, dim>       &P,
    Tensor<4, dim>       &A) const
  {
    const double         J   = determinant(F);
    const double         g   = Volume::value(J);
    const double         dg  = Volume::first_derivative(J);
    const double         d2g = Volume::second_derivative(J);
    const Tensor<2, dim> cof = cofactor(F);
    const double         c1  = lambda * dg * dg + (lambda * g - mu) * d2g;
    const double         c2  = (lambda * g - mu) * dg;

    P = mu * F + c2 * cof;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        for (unsigned int k = 0; k < dim; ++k)
          for (unsigned int l = 0; l < dim; ++l)
            A[i][j][k][l] = (i == k && j == l ? mu : 0.) +
                            c1 * cof[i][j] * cof[k][l] +
                            c2 * cofactor_derivative(F, i, j, k, l);
  }

  template class NeoHookeanFamily<1, LogVolume>;
  template class NeoHookeanFamily<2, LogVolume>;
  template class NeoHookeanFamily<3, LogVolume>;
  template class NeoHookeanFamily<1, CubicVolume>;
  template class NeoHookeanFamily<2, CubicVolume>;
  template class NeoHookeanFamily<3, CubicVolume>;

TISSUEFEM_REGISTER_MATERIAL(
    NeoHookean,
    "neo-Hookean",
    "compressible neo-Hookean, Psi = mu/2 (tr F^T F - d) - mu log J + "
    "lambda/2 log^2 J (Teran eq 2.8a); undefined for det F <= 0.")
  TISSUEFEM_REGISTER_MATERIAL(
    RobustNeoHookean,
    "robust neo-Hookean",
    "inversion-robust neo-Hookean: log J replaced by its cubic Taylor "
    "expansion r(J) about J = 1 (Teran eq 2.9); defined for every F.")
  
} // namespace tissuefem::materials
