#pragma once

#include <tissuefem/materials/energy_material.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>

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
      SmallMatrix<dim, double> R;
      double                   trace_S;
      Tensor<2, dim>           P;
      polar_stress(F, R, trace_S, P);
      return P;
    }

    bool
    admits_inversion() const override
    {
      return false;
    }

    bool
    has_hand_coded_tangent() const override
    {
      return true;
    }

    bool
    has_simplex_stiffness() const override
    {
      return dim == 3;
    }

    /**
     * P and a linear simplex's node blocks (interface.h) from the tangent's
     * three parts (hand_coded_stress_and_tangent()), without writing out A:
     *
     *   K_kl = 2 mu (g_k . g_l) I + lambda h_k (x) h_l + c [u_l0 x h_k,
     *          u_l1 x h_k, u_l2 x h_k] (columns),
     *
     * with h_k = R g_k, c = lambda (tr S - 3) - 2 mu and u_lj = R G^{-1}
     * (g_l x r_j), r_j the j-th row of R: dR for dF = e_j e_n^T is R [G^{-1}
     * (e_n x r_j)]x, its sum over n weighted by g_l,n is R [G^{-1} (g_l x
     * r_j)]x, and R [v]x g_k = (R v) x (R g_k). About 600 operations for
     * the four nodes' ten blocks, against about 1,100 for A's 81 entries
     * and their contraction. 2D models use the default.
     */
    void
    simplex_stiffness(const Tensor<2, dim> &F,
                      const Tensor<1, dim> &fibre,
                      const Tensor<1, dim> *g,
                      Tensor<2, dim>       &P,
                      double               *K) const override
    {
      if constexpr (dim != 3)
        {
          Interface<dim>::simplex_stiffness(F, fibre, g, P, K);
          return;
        }
      else
        {
          SmallMatrix<3, double> R;
          double                 trace_S;
          polar_stress(F, R, trace_S, P);
          const double       c = lambda * (trace_S - 3.) - 2. * mu;
          const Tensor<2, 3> G_inverse
            = rotation_gradient_inverse<dim>(F, R, trace_S);
          Tensor<2, 3> rotation;
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              rotation[i][j] = R[i][j];
          std::array<Tensor<1, 3>, 4>                h;
          std::array<std::array<Tensor<1, 3>, 3>, 4> u;
          for (unsigned int k = 0; k < 4; ++k)
            {
              h[k] = rotation * g[k];
              for (unsigned int j = 0; j < 3; ++j)
                u[k][j] = rotation
                          * (G_inverse * cross_product_3d(g[k], rotation[j]));
            }
          for (unsigned int k = 0, b = 0; k < 4; ++k)
            for (unsigned int l = k; l < 4; ++l, ++b)
              {
                double      *block = K + 9 * b;
                const double shear = 2. * mu * (g[k] * g[l]);
                for (unsigned int j = 0; j < 3; ++j)
                  {
                    const Tensor<1, 3> turn = cross_product_3d(u[l][j], h[k]);
                    for (unsigned int i = 0; i < 3; ++i)
                      block[3 * i + j] = lambda * h[k][i] * h[l][j]
                                         + c * turn[i] + (i == j ? shear : 0.);
                  }
              }
        }
    }

  protected:
    /**
     * P as first_piola_kirchhoff() and A = dP/dF in closed form, instead of
     * AD through every iteration of the polar decomposition (measured: 1.7
     * s of a 2.1 s step on SOFA's 101,250-tetrahedron beam). Differentiating
     * P = 2 mu (F - R) + lambda (tr S - d) R,
     *
     *   dP = 2 mu (dF - dR) + lambda (R : dF) R + lambda (tr S - d) dR,
     *
     * since d tr S = d tr(R^T F) = R : dF (the term tr(dR^T F) = -tr(W S)
     * vanishes: W = R^T dR is skew, S symmetric). The skew part of R^T dF =
     * W S + dS gives W S + S W = R^T dF - dF^T R =: M. In 3D, with W = [w]x,
     * W S + S W = [(tr S I - S) w]x, so w = (tr S I - S)^{-1} axial(M); in
     * 2D W = w J (J the rotation by 90 degrees) and W S + S W = w tr S J, so
     * w = M_10 / tr S (McAdams et al. 2011 derive dR so). tr S I - S is
     * positive definite where det F > 0, the model's domain.
     */
    void
    hand_coded_stress_and_tangent(const Tensor<2, dim> &F,
                                  const Tensor<1, dim> &fibre,
                                  Tensor<2, dim>       &P,
                                  Tensor<4, dim>       &A) const override
    {
      (void)fibre;
      SmallMatrix<dim, double> R;
      double                   trace_S;
      polar_stress(F, R, trace_S, P);
      const double rotation_factor = lambda * (trace_S - double(dim)) - 2. * mu;
      Tensor<2, 3> G_inverse;
      if constexpr (dim == 3)
        G_inverse = rotation_gradient_inverse<dim>(F, R, trace_S);
      for (unsigned int k = 0; k < dim; ++k)
        for (unsigned int l = 0; l < dim; ++l)
          {
            // dR for dF = e_k e_l^T: (R^T dF)_ab = R_ka delta_bl.
            Tensor<2, dim> dR;
            if constexpr (dim == 2)
              {
                const double w
                  = ((l == 0 ? R[k][1] : 0.) - (l == 1 ? R[k][0] : 0.))
                    / trace_S;
                // dR = R W, W = w [[0, -1], [1, 0]].
                for (unsigned int i = 0; i < 2; ++i)
                  {
                    dR[i][0] = w * R[i][1];
                    dR[i][1] = -w * R[i][0];
                  }
              }
            else if constexpr (dim == 3)
              {
                // axial(M) = (M_21, M_02, M_10), M_ab = R_ka delta_bl -
                // R_kb delta_al.
                Tensor<1, 3> a;
                a[0] = (l == 1 ? R[k][2] : 0.) - (l == 2 ? R[k][1] : 0.);
                a[1] = (l == 2 ? R[k][0] : 0.) - (l == 0 ? R[k][2] : 0.);
                a[2] = (l == 0 ? R[k][1] : 0.) - (l == 1 ? R[k][0] : 0.);
                const Tensor<1, 3> w = G_inverse * a;
                // dR = R [w]x, [w]x = [[0, -w2, w1], [w2, 0, -w0],
                // [-w1, w0, 0]].
                for (unsigned int i = 0; i < 3; ++i)
                  {
                    dR[i][0] = R[i][1] * w[2] - R[i][2] * w[1];
                    dR[i][1] = R[i][2] * w[0] - R[i][0] * w[2];
                    dR[i][2] = R[i][0] * w[1] - R[i][1] * w[0];
                  }
              }
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = 0; j < dim; ++j)
                A[i][j][k][l] = lambda * R[i][j] * R[k][l]
                                + rotation_factor * dR[i][j]
                                + (i == k && j == l ? 2. * mu : 0.);
          }
    }

  private:
    const double lambda;
    const double mu;

    /// G^{-1} = (tr S I - S)^{-1} in 3D, with S = R^T F (see
    /// hand_coded_stress_and_tangent()).
    /// (A member template: the class's explicit instantiation in 1D and 2D
    /// leaves it out.)
    template <int d>
    static Tensor<2, 3>
    rotation_gradient_inverse(const Tensor<2, d>           &F,
                              const SmallMatrix<d, double> &R,
                              const double                  trace_S)
    {
      Tensor<2, 3> G;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          {
            double S_ij = 0;
            for (unsigned int m = 0; m < 3; ++m)
              S_ij += R[m][i] * F[m][j];
            G[i][j] = (i == j ? trace_S : 0.) - S_ij;
          }
      // S is symmetric up to round-off; so is G.
      return invert(0.5 * (G + transpose(G)));
    }

    /// The polar rotation @p R of @p F, tr S = R : F and P = 2 mu (F - R)
    /// + lambda (tr S - d) R, in double precision.
    void
    polar_stress(const Tensor<2, dim>     &F,
                 SmallMatrix<dim, double> &R,
                 double                   &trace_S,
                 Tensor<2, dim>           &P) const
    {
      SmallMatrix<dim, double> matrix;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          matrix[i][j] = F[i][j];
      R       = rotation(matrix);
      trace_S = 0;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          trace_S += R[i][j] * F[i][j];
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          P[i][j] = 2. * mu * (F[i][j] - R[i][j])
                    + lambda * (trace_S - double(dim)) * R[i][j];
    }

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
      else if constexpr (std::is_arithmetic_v<Number>)
        R = rotation_3d(F);
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
              // derivatives (which converge with them) settle too.
              if (change < 1e-15 && iteration > 2)
                break;
            }
        }
      return R;
    }

    /**
     * The 3D polar rotation of @p F in double precision, by the same scaled
     * Newton iteration, written for the explicit methods' force loop and the
     * closed-form tangent (where it was the corotational step's extra cost
     * over St Venant-Kirchhoff's): the cofactor once per sweep, one division,
     * and the Frobenius scaling (Higham 1986, doc/references.md) on the
     * first sweep and while sweeps still change R by more than 0.1: nearer
     * a rotation it changes little and costs two square roots, but far from
     * one (F nearly singular) unscaled sweeps only halve the error each. Near
     * convergence, with X = R (I + E), one sweep leaves E^2 / 2 and changes X
     * by about |E|: so a sweep that changes it by less than 4e-7 leaves an
     * error below 1e-13, and it stops there instead of making one more sweep to
     * see it. Measured on random rotations of stretches of 0.3 to 30 %: 1.9-2.0
     * times faster than the general loop (which runs to a change of 1e-9),
     * 3-4.8 sweeps, R orthogonal and R^T F symmetric to 4e-13.
     */
    static SmallMatrix<3, double>
    rotation_3d(const SmallMatrix<3, double> &F)
    {
      auto frobenius = [](const SmallMatrix<3, double> &A) {
        double result = 0;
        for (const auto &row : A)
          for (const double a : row)
            result += a * a;
        return result;
      };
      SmallMatrix<3, double> R      = F, C;
      bool                   scaled = true;
      for (unsigned int iteration = 0; iteration < 30; ++iteration)
        {
          // C = cof R = det R R^{-T}.
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              {
                const unsigned int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
                const unsigned int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
                C[i][j] = R[i1][j1] * R[i2][j2] - R[i1][j2] * R[i2][j1];
              }
          const double J
            = R[0][0] * C[0][0] + R[0][1] * C[0][1] + R[0][2] * C[0][2];
          // R <- (g R + R^{-T} / g) / 2 = a R + b C.
          double a = 0.5, b = 0.5 / J;
          if (scaled)
            {
              const double g
                = std::sqrt(std::sqrt(frobenius(C) / (J * J * frobenius(R))));
              a = 0.5 * g;
              b = 0.5 / (g * J);
            }
          double change = 0;
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              {
                const double next = a * R[i][j] + b * C[i][j];
                change            = std::max(change, std::abs(next - R[i][j]));
                R[i][j]           = next;
              }
          scaled = change > 0.1;
          if (change < 4e-7)
            break;
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
