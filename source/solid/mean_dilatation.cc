#include <tissuefem/solid/mean_dilatation.h>

#include <Sacado.hpp>

#include <cmath>

namespace tissuefem::solid
{
  template <int dim>
  double
  mean_dilatation(const std::vector<Tensor<2, dim>> &F,
                  const double                      *JxW,
                  const unsigned int                 n_q)
  {
    double volume = 0, deformed = 0, smallest = 1;
    for (unsigned int q = 0; q < n_q; ++q)
      {
        const double J = determinant(F[q]);
        smallest       = std::min(smallest, J);
        volume += JxW[q];
        deformed += J * JxW[q];
      }
    return smallest > 0 ? deformed / volume : std::min(smallest, 0.);
  }


  template <int dim>
  Tensor<2, dim>
  modified_deformation_gradient(const Tensor<2, dim> &F, const double theta)
  {
    return std::pow(theta / determinant(F), 1. / dim) * F;
  }


  template <int dim>
  bool
  apply_mean_dilatation(std::vector<Tensor<2, dim>> &F,
                        const double                *JxW,
                        const unsigned int           n_q,
                        const double                 carried)
  {
    const double theta = mean_dilatation(F, JxW, n_q);
    return theta > 0 && apply_dilatation(F, n_q, carried * theta);
  }


  template <int dim>
  bool
  apply_dilatation(std::vector<Tensor<2, dim>> &F,
                   const unsigned int           n_q,
                   const double                 theta)
  {
    for (unsigned int q = 0; q < n_q; ++q)
      if (!(theta / determinant(F[q]) > 0))
        return false;
    for (unsigned int q = 0; q < n_q; ++q)
      F[q] = modified_deformation_gradient(F[q], theta);
    return true;
  }


  template <int dim>
  void
  mean_dilatation_stress(const Tensor<2, dim>     &F,
                         const double              theta,
                         const Tensor<2, dim>     &P_bar,
                         MeanDilatationPoint<dim> &point)
  {
    const double         s     = std::pow(theta / determinant(F), 1. / dim);
    const double         power = s * scalar_product(P_bar, F); // Pbar : Fbar
    const Tensor<2, dim> F_inverse_transpose = transpose(invert(F));
    point.phi_F     = s * P_bar - (power / dim) * F_inverse_transpose;
    point.phi_theta = power / (dim * theta);
  }


  template <int dim>
  void
  mean_dilatation_stress_and_tangent(const Tensor<2, dim>     &F,
                                     const double              theta,
                                     const Tensor<2, dim>     &P_bar,
                                     const Tensor<4, dim>     &A_bar,
                                     MeanDilatationPoint<dim> &point)
  {
    // g(F, theta) = s F: dg_e/dF_kl = s delta_e,kl + F_e S_kl, dg_e/dtheta =
    // F_e s_t; the second derivatives add S and s_t to the identity parts
    // and F_e times those of s. phi's derivatives chain Pbar and Abar.
    const double         J     = determinant(F);
    const double         s     = std::pow(theta / J, 1. / dim);
    const Tensor<2, dim> F_inv = invert(F);
    const Tensor<2, dim> S     = -(s / dim) * transpose(F_inv);
    const double         s_t   = s / (dim * theta);
    const double s_tt = (1. / dim) * (1. / dim - 1.) * s / (theta * theta);
    const Tensor<2, dim> s_Ft = -(s_t / dim) * transpose(F_inv);
    const double         PF   = scalar_product(P_bar, F);
    Tensor<2, dim>       AF, FA; // Abar : F and F : Abar
    for (unsigned int k = 0; k < dim; ++k)
      for (unsigned int l = 0; l < dim; ++l)
        for (unsigned int m = 0; m < dim; ++m)
          for (unsigned int n = 0; n < dim; ++n)
            {
              AF[k][l] += A_bar[k][l][m][n] * F[m][n];
              FA[m][n] += F[k][l] * A_bar[k][l][m][n];
            }
    const double FAF = scalar_product(FA, F);
    point.phi_F      = s * P_bar + PF * S;
    point.phi_theta  = PF * s_t;
    for (unsigned int k = 0; k < dim; ++k)
      for (unsigned int l = 0; l < dim; ++l)
        {
          point.phi_F_theta[k][l] = s_t * (s * AF[k][l] + S[k][l] * FAF)
                                    + s_t * P_bar[k][l] + PF * s_Ft[k][l];
          for (unsigned int m = 0; m < dim; ++m)
            for (unsigned int n = 0; n < dim; ++n)
              {
                // d2s/dF_kl dF_mn
                const double s_FF = s / (dim * dim) * F_inv[l][k] * F_inv[n][m]
                                    + s / dim * F_inv[l][m] * F_inv[n][k];
                point.phi_FF[k][l][m][n]
                  = s * s * A_bar[k][l][m][n] + s * S[m][n] * AF[k][l]
                    + s * S[k][l] * FA[m][n] + S[k][l] * S[m][n] * FAF
                    + P_bar[k][l] * S[m][n] + P_bar[m][n] * S[k][l] + PF * s_FF;
              }
        }
    point.phi_theta_theta = s_t * s_t * FAF + PF * s_tt;
  }


  template <int dim>
  void
  mean_dilatation_stress_and_tangent_by_ad(const Tensor<2, dim>     &F,
                                           const double              theta,
                                           const Tensor<2, dim>     &P_bar,
                                           const Tensor<4, dim>     &A_bar,
                                           MeanDilatationPoint<dim> &point)
  {
    // Variables x = (F_00, F_01, ..., F_dd, theta); g(x) = Fbar.
    constexpr int n = dim * dim + 1;
    using Inner     = Sacado::Fad::SFad<double, n>;
    using Number    = Sacado::Fad::SFad<Inner, n>;
    Number x[n];
    for (int m = 0; m < n; ++m)
      {
        const double value = m < dim * dim ? F[m / dim][m % dim] : theta;
        x[m]               = Number(n, m, Inner(n, m, value));
      }
    Number J;
    if constexpr (dim == 1)
      J = x[0];
    else if constexpr (dim == 2)
      J = x[0] * x[3] - x[1] * x[2];
    else
      J = x[0] * (x[4] * x[8] - x[5] * x[7])
          - x[1] * (x[3] * x[8] - x[5] * x[6])
          + x[2] * (x[3] * x[7] - x[4] * x[6]);
    const Number s = pow(x[dim * dim] / J, 1. / dim);
    double       g1[dim * dim][n], g2[dim * dim][n][n];
    for (int e = 0; e < dim * dim; ++e)
      {
        const Number g = s * x[e];
        for (int m = 0; m < n; ++m)
          {
            g1[e][m] = g.dx(m).val();
            for (int k = 0; k < n; ++k)
              g2[e][m][k] = g.dx(m).dx(k);
          }
      }
    // phi_m = Pbar_e g_e,m;  phi_mk = g_e,m Abar_ef g_f,k + Pbar_e g_e,mk.
    double phi1[n], phi2[n][n], T[n][dim * dim];
    for (int m = 0; m < n; ++m)
      {
        phi1[m] = 0;
        for (int f = 0; f < dim * dim; ++f)
          T[m][f] = 0;
        for (int e = 0; e < dim * dim; ++e)
          {
            phi1[m] += P_bar[e / dim][e % dim] * g1[e][m];
            if (g1[e][m] != 0)
              for (int f = 0; f < dim * dim; ++f)
                T[m][f] += g1[e][m] * A_bar[e / dim][e % dim][f / dim][f % dim];
          }
      }
    for (int m = 0; m < n; ++m)
      for (int k = m; k < n; ++k)
        {
          double value = 0;
          for (int e = 0; e < dim * dim; ++e)
            value += T[m][e] * g1[e][k] + P_bar[e / dim][e % dim] * g2[e][m][k];
          phi2[m][k] = phi2[k][m] = value;
        }
    constexpr int t = dim * dim;
    for (int m = 0; m < t; ++m)
      {
        point.phi_F[m / dim][m % dim]       = phi1[m];
        point.phi_F_theta[m / dim][m % dim] = phi2[m][t];
        for (int k = 0; k < t; ++k)
          point.phi_FF[m / dim][m % dim][k / dim][k % dim] = phi2[m][k];
      }
    point.phi_theta       = phi1[t];
    point.phi_theta_theta = phi2[t][t];
  }


#define TISSUEFEM_INSTANTIATE(dim)                                          \
  template double mean_dilatation<dim>(const std::vector<Tensor<2, dim>> &, \
                                       const double *,                      \
                                       const unsigned int);                 \
  template Tensor<2, dim> modified_deformation_gradient<dim>(               \
    const Tensor<2, dim> &, const double);                                  \
  template bool apply_mean_dilatation<dim>(std::vector<Tensor<2, dim>> &,   \
                                           const double *,                  \
                                           const unsigned int,              \
                                           const double);                   \
  template bool apply_dilatation<dim>(std::vector<Tensor<2, dim>> &,        \
                                      const unsigned int,                   \
                                      const double);                        \
  template void mean_dilatation_stress<dim>(const Tensor<2, dim> &,         \
                                            const double,                   \
                                            const Tensor<2, dim> &,         \
                                            MeanDilatationPoint<dim> &);    \
  template void mean_dilatation_stress_and_tangent<dim>(                    \
    const Tensor<2, dim> &,                                                 \
    const double,                                                           \
    const Tensor<2, dim> &,                                                 \
    const Tensor<4, dim> &,                                                 \
    MeanDilatationPoint<dim> &);                                            \
  template void mean_dilatation_stress_and_tangent_by_ad<dim>(              \
    const Tensor<2, dim> &,                                                 \
    const double,                                                           \
    const Tensor<2, dim> &,                                                 \
    const Tensor<4, dim> &,                                                 \
    MeanDilatationPoint<dim> &);
  TISSUEFEM_INSTANTIATE(1)
  TISSUEFEM_INSTANTIATE(2)
  TISSUEFEM_INSTANTIATE(3)
#undef TISSUEFEM_INSTANTIATE
} // namespace tissuefem::solid
