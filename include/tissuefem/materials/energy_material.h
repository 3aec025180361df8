#pragma once

#include <deal.II/differentiation/ad.h>
#include <deal.II/fe/fe_values_extractors.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/materials/interface.h>
#include <tissuefem/materials/kinematics.h>
#include <tissuefem/materials/small_matrix.h>

#include <Sacado.hpp>

#include <type_traits>

namespace tissuefem::materials
{
  /// Whether @p Model writes its energy as a function of (I1, J).
  template <typename Model, typename = void>
  struct HasInvariantEnergy : std::false_type
  {
  };
  template <typename Model>
  struct HasInvariantEnergy<Model,
                            std::void_t<decltype(std::declval<const Model &>()
                                                   .invariant_energy(0., 0.))>>
      : std::true_type
  {
  };

  /// Whether @p Model writes its energy in C = F^T F (energy_in_C).
  template <typename Model, int dim, typename = void>
  struct HasEnergyInC : std::false_type
  {
  };
  template <typename Model, int dim>
  struct HasEnergyInC<
    Model,
    dim,
    std::void_t<decltype(std::declval<const Model &>().energy_in_C(
      std::declval<const SmallMatrix<dim, double> &>(),
      std::declval<const Tensor<1, dim> &>()))>> : std::true_type
  {
  };

  /**
   * For models whose S = dPsi/dE is linear in E (St Venant-Kirchhoff and
   * its transversely isotropic variant): P = F S and the hand-coded
   * tangent A_iJkL = delta_ik S_LJ + F_iM F_kQ CC_MJLQ, whose material part
   * the model adds (add_material_tangent()).
   */
  template <int dim, typename Model>
  void
  quadratic_in_E_stress_and_tangent(const Model          &model,
                                    const Tensor<2, dim> &F,
                                    const Tensor<1, dim> &fibre,
                                    Tensor<2, dim>       &P,
                                    Tensor<4, dim>       &A)
  {
    const Tensor<2, dim> E
      = 0.5 * (transpose(F) * F - unit_symmetric_tensor<dim>());
    const Tensor<2, dim> S = model.second_piola_kirchhoff(E, fibre);
    P                      = F * S;
    A                      = 0;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int J = 0; J < dim; ++J)
        for (unsigned int L = 0; L < dim; ++L)
          A[i][J][i][L] = S[L][J];
    model.add_material_tangent(F, fibre, A);
  }


  template <typename Model, int dim, typename = void>
  struct HasClosedFormStress : std::false_type
  {
  };
  template <typename Model, int dim>
  struct HasClosedFormStress<
    Model,
    dim,
    std::void_t<decltype(std::declval<const Model &>().second_piola_kirchhoff(
      std::declval<const Tensor<2, dim> &>(),
      std::declval<const Tensor<1, dim> &>()))>> : std::true_type
  {
  };

  /// Whether @p Model gives its first Piola-Kirchhoff stress in closed form,
  /// first_piola_kirchhoff(F, fibre).
  template <typename Model, int dim, typename = void>
  struct HasClosedFormFirstPiola : std::false_type
  {
  };
  template <typename Model, int dim>
  struct HasClosedFormFirstPiola<
    Model,
    dim,
    std::void_t<decltype(std::declval<const Model &>().first_piola_kirchhoff(
      std::declval<const Tensor<2, dim> &>(),
      std::declval<const Tensor<1, dim> &>()))>> : std::true_type
  {
  };

  /**
   * Turns an energy density into a material: @p Model writes
   *
   *   template <typename Number>
   *   Number energy(const SmallMatrix<dim, Number> &F,
   *                 const Tensor<1, dim> &fibre) const;
   *
   * once, and this class differentiates it. An isotropic model may in
   * addition write its energy in the invariants I1 = tr F^T F and J = det F,
   *
   *   template <typename Number>
   *   Number invariant_energy(const Number &I1, const Number &J) const;
   *
   * and a model written in C = F^T F may provide
   *
   *   template <typename Number>
   *   Number energy_in_C(const SmallMatrix<dim, Number> &C,
   *                      const Tensor<1, dim> &fibre) const;
   *
   * which enables the edge-length element (Jeffrey eqs 19-31).
   *
   * Tangent methods:
   * - automatic differentiation: for invariant models, the five first and
   *   second derivatives of Psi(I1, J) come from two-variable nested Sacado
   *   numbers and are chained with the closed-form derivatives of I1 and J
   *   (dI1/dF = 2F, dJ/dF = cof F); otherwise as below.
   * - automatic differentiation in F: the d*d entries of F are seeded as
   *   fixed-size forward AD numbers nested twice, so one energy evaluation
   *   yields Psi, P and dP/dF, with all storage on the stack.
   * - deal.II AD helper: deal.II's ScalarFunction helper (dynamic Sacado
   *   numbers), the approach of deal.II's step-71; slowest.
   */
  template <int dim, typename Model>
  class EnergyMaterial : public Interface<dim>
  {
  public:
    static constexpr int n_entries = dim * dim;
    using FirstOrder               = Sacado::Fad::SFad<double, n_entries>;
    using SecondOrder              = Sacado::Fad::SFad<FirstOrder, n_entries>;

    double
    energy_density(const Tensor<2, dim> &F,
                   const Tensor<1, dim> &fibre) const override
    {
      SmallMatrix<dim, double> F_small;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          F_small[i][j] = F[i][j];
      return model().energy(F_small, fibre);
    }

    /**
     * P = dPsi/dF by the cheapest means the model allows (this is the
     * explicit methods' inner loop): a closed-form S = dPsi/dE where the
     * model gives one (P = F S); for invariant models two directions
     * (I1, J), P = 2 Psi_1 F + Psi_J cof F; for models written in C the
     * dim (dim + 1) / 2 independent entries of the symmetric C, P = F S with
     * S = 2 dPsi/dC; otherwise the dim^2 entries of F.
     */
    Tensor<2, dim>
    stress(const Tensor<2, dim> &F, const Tensor<1, dim> &fibre) const override
    {
      if constexpr (HasClosedFormFirstPiola<Model, dim>::value)
        return model().first_piola_kirchhoff(F, fibre);
      else if constexpr (HasClosedFormStress<Model, dim>::value)
        {
          const Tensor<2, dim> E
            = 0.5 * (transpose(F) * F - unit_symmetric_tensor<dim>());
          return F * model().second_piola_kirchhoff(E, fibre);
        }
      else if constexpr (HasInvariantEnergy<Model>::value)
        {
          using Number = Sacado::Fad::SFad<double, 2>;
          const Number I1(2, 0, F.norm_square());
          const Number J(2, 1, determinant(F));
          const Number psi = model().invariant_energy(I1, J);
          return (2. * psi.dx(0)) * F + psi.dx(1) * cofactor(F);
        }
      else if constexpr (HasEnergyInC<Model, dim>::value)
        {
          // One AD variable per unordered pair (i, j): seeding C_ij and C_ji
          // with it gives dPsi/dvar = 2 dPsi/dC_ij off the diagonal and
          // dPsi/dC_ii on it, so S_ij = dPsi/dvar (i != j), 2 dPsi/dvar
          // (i = j).
          constexpr int n_symmetric  = dim * (dim + 1) / 2;
          using Number               = Sacado::Fad::SFad<double, n_symmetric>;
          const Tensor<2, dim>     C = transpose(F) * F;
          SmallMatrix<dim, Number> C_ad;
          unsigned int             index[dim][dim];
          for (unsigned int i = 0, n = 0; i < dim; ++i)
            for (unsigned int j = i; j < dim; ++j, ++n)
              {
                index[i][j] = index[j][i] = n;
                C_ad[i][j] = C_ad[j][i] = Number(n_symmetric, n, C[i][j]);
              }
          const Number   psi = model().energy_in_C(C_ad, fibre);
          Tensor<2, dim> S;
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = 0; j < dim; ++j)
              S[i][j] = (i == j ? 2. : 1.) * psi.dx(index[i][j]);
          return F * S;
        }
      SmallMatrix<dim, FirstOrder> F_ad;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          F_ad[i][j] = FirstOrder(n_entries, i * dim + j, F[i][j]);
      const FirstOrder psi = model().energy(F_ad, fibre);
      Tensor<2, dim>   P;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          P[i][j] = psi.dx(i * dim + j);
      return P;
    }

    void
    stress_and_tangent(const Tensor<2, dim> &F,
                       const Tensor<1, dim> &fibre,
                       Tensor<2, dim>       &P,
                       Tensor<4, dim>       &A,
                       const TangentMethod   method) const override
    {
      switch (method)
        {
          case TangentMethod::automatic_differentiation:
            if constexpr (HasInvariantEnergy<Model>::value)
              invariant_ad(F, P, A);
            else if constexpr (HasEnergyInC<Model, dim>::value)
              right_cauchy_green_ad(F, fibre, P, A);
            else
              fixed_size_ad(F, fibre, P, A);
            return;
          case TangentMethod::automatic_differentiation_in_F:
            fixed_size_ad(F, fibre, P, A);
            return;
          case TangentMethod::dealii_ad_helper:
            dealii_helper(F, fibre, P, A);
            return;
          case TangentMethod::hand_coded:
            hand_coded_stress_and_tangent(F, fibre, P, A);
            return;
          case TangentMethod::fastest:
            if (this->has_hand_coded_tangent())
              hand_coded_stress_and_tangent(F, fibre, P, A);
            else
              stress_and_tangent(
                F, fibre, P, A, TangentMethod::automatic_differentiation);
            return;
        }
    }

    // The batch forms call this class's own functions (no virtual dispatch
    // per point).
    void
    stresses(const unsigned int    n,
             const Tensor<2, dim> *F,
             const Tensor<1, dim> *fibre,
             Tensor<2, dim>       *P) const override
    {
      for (unsigned int i = 0; i < n; ++i)
        P[i] = EnergyMaterial::stress(F[i], fibre[i]);
    }

    void
    stresses_and_tangents(const unsigned int    n,
                          const Tensor<2, dim> *F,
                          const Tensor<1, dim> *fibre,
                          Tensor<2, dim>       *P,
                          Tensor<4, dim>       *A,
                          const TangentMethod   method) const override
    {
      for (unsigned int i = 0; i < n; ++i)
        EnergyMaterial::stress_and_tangent(F[i], fibre[i], P[i], A[i], method);
    }

    bool
    has_edge_length_form() const override
    {
      return HasEnergyInC<Model, dim>::value;
    }

    void
    edge_length_element(const std::vector<Tensor<1, dim>> &alpha,
                        const double                       volume,
                        const std::vector<Tensor<1, dim>> &Q,
                        const Tensor<1, dim>              &fibre,
                        double                            &energy,
                        std::vector<double>               &forces,
                        std::vector<double> *stiffness) const override
    {
      if constexpr (HasEnergyInC<Model, dim>::value)
        edge_length_ad(alpha, volume, Q, fibre, energy, forces, stiffness);
      else
        Interface<dim>::edge_length_element(
          alpha, volume, Q, fibre, energy, forces, stiffness);
    }

  protected:
    /// Materials with a closed-form tangent override this and
    /// has_hand_coded_tangent().
    virtual void
    hand_coded_stress_and_tangent(const Tensor<2, dim> &,
                                  const Tensor<1, dim> &,
                                  Tensor<2, dim> &,
                                  Tensor<4, dim> &) const
    {
      throw InputError("Parameter 'Materials/Tangent': this material has no "
                       "hand-coded tangent; use 'automatic differentiation'");
    }

  private:
    const Model &
    model() const
    {
      return static_cast<const Model &>(*this);
    }

    /**
     * P = 2 Psi_1 F + Psi_J cof F and
     * A = 4 Psi_11 F x F + 2 Psi_1J (F x cof + cof x F) + Psi_JJ cof x cof
     *     + 2 Psi_1 I + Psi_J dcof/dF,
     * with the Psi derivatives from AD of invariant_energy().
     */
    void
    invariant_ad(const Tensor<2, dim> &F,
                 Tensor<2, dim>       &P,
                 Tensor<4, dim>       &A) const
    {
      using Inner = Sacado::Fad::SFad<double, 2>;
      using Outer = Sacado::Fad::SFad<Inner, 2>;
      const Outer          I1(2, 0, Inner(2, 0, F.norm_square()));
      const Outer          J(2, 1, Inner(2, 1, determinant(F)));
      const Outer          psi    = model().invariant_energy(I1, J);
      const double         psi_1  = psi.dx(0).val();
      const double         psi_J  = psi.dx(1).val();
      const double         psi_11 = psi.dx(0).dx(0);
      const double         psi_1J = psi.dx(0).dx(1);
      const double         psi_JJ = psi.dx(1).dx(1);
      const Tensor<2, dim> cof    = cofactor(F);

      P = (2. * psi_1) * F + psi_J * cof;
      // One fused pass: A_ijkl = x_ij F_kl + y_ij cof_kl + 2 Psi_1 d_ik d_jl
      // with x = 4 Psi_11 F + 2 Psi_1J cof and y = 2 Psi_1J F + Psi_JJ cof.
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          {
            const double x = 4. * psi_11 * F[i][j] + 2. * psi_1J * cof[i][j];
            const double y = 2. * psi_1J * F[i][j] + psi_JJ * cof[i][j];
            for (unsigned int k = 0; k < dim; ++k)
              for (unsigned int l = 0; l < dim; ++l)
                A[i][j][k][l] = x * F[k][l] + y * cof[k][l];
            A[i][j][i][j] += 2. * psi_1;
          }
      add_cofactor_derivative(F, psi_J, A);
    }

    /**
     * For models written in C: the dim (dim + 1) / 2 independent entries of
     * the symmetric C seeded as nested forward AD numbers (36 second
     * derivatives in 3D instead of 81 in F), one variable per unordered
     * pair (i, j) seeding C_ij and C_ji, so that with m = 2 off the
     * diagonal and 1 on it, dPsi/dC_ij = d1_p / m_p and d2Psi/dC_ij dC_kl =
     * d2_pq / (m_p m_q). Then S = 2 dPsi/dC, CC = 4 d2Psi/dC dC, P = F S and
     * A_iJkL = delta_ik S_LJ + F_iM F_kQ CC_MJLQ (P = F S differentiated
     * with dE/dF from E = (F^T F - I)/2 and the minor symmetry of CC).
     */
    void
    right_cauchy_green_ad(const Tensor<2, dim> &F,
                          const Tensor<1, dim> &fibre,
                          Tensor<2, dim>       &P,
                          Tensor<4, dim>       &A) const
    {
      constexpr int n           = dim * (dim + 1) / 2;
      using Inner               = Sacado::Fad::SFad<double, n>;
      using Outer               = Sacado::Fad::SFad<Inner, n>;
      const Tensor<2, dim>    C = transpose(F) * F;
      SmallMatrix<dim, Outer> C_ad;
      unsigned int            index[dim][dim];
      double                  weight[n];
      for (unsigned int i = 0, p = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j, ++p)
          {
            index[i][j] = index[j][i] = p;
            weight[p]                 = (i == j ? 1. : 2.);
            C_ad[i][j] = C_ad[j][i] = Outer(n, p, Inner(n, p, C[i][j]));
          }
      const Outer    psi = model().energy_in_C(C_ad, fibre);
      Tensor<2, dim> S;
      Tensor<4, dim> CC;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          {
            const unsigned int p = index[i][j];
            S[i][j]              = 2. * psi.dx(p).val() / weight[p];
            for (unsigned int k = 0; k < dim; ++k)
              for (unsigned int l = 0; l < dim; ++l)
                {
                  const unsigned int q = index[k][l];
                  CC[i][j][k][l]
                    = 4. * psi.dx(p).dx(q) / (weight[p] * weight[q]);
                }
          }
      P = F * S;
      // G_kJL = F_kQ CC_MJLQ contracted later with F_iM: G[M][J][L][k].
      Tensor<4, dim> G;
      for (unsigned int M = 0; M < dim; ++M)
        for (unsigned int J = 0; J < dim; ++J)
          for (unsigned int L = 0; L < dim; ++L)
            for (unsigned int k = 0; k < dim; ++k)
              {
                double sum = 0;
                for (unsigned int Q = 0; Q < dim; ++Q)
                  sum += F[k][Q] * CC[M][J][L][Q];
                G[M][J][L][k] = sum;
              }
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int J = 0; J < dim; ++J)
          for (unsigned int k = 0; k < dim; ++k)
            for (unsigned int L = 0; L < dim; ++L)
              {
                double sum = (i == k) ? S[L][J] : 0.;
                for (unsigned int M = 0; M < dim; ++M)
                  sum += F[i][M] * G[M][J][L][k];
                A[i][J][k][L] = sum;
              }
    }

    void
    fixed_size_ad(const Tensor<2, dim> &F,
                  const Tensor<1, dim> &fibre,
                  Tensor<2, dim>       &P,
                  Tensor<4, dim>       &A) const
    {
      SmallMatrix<dim, SecondOrder> F_ad;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          {
            const int index = i * dim + j;
            F_ad[i][j]      = SecondOrder(n_entries,
                                     index,
                                     FirstOrder(n_entries, index, F[i][j]));
          }
      const SecondOrder psi = model().energy(F_ad, fibre);
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          {
            const FirstOrder &dpsi = psi.dx(i * dim + j);
            P[i][j]                = dpsi.val();
            for (unsigned int k = 0; k < dim; ++k)
              for (unsigned int l = 0; l < dim; ++l)
                A[i][j][k][l] = dpsi.dx(k * dim + l);
          }
    }

    void
    dealii_helper(const Tensor<2, dim> &F,
                  const Tensor<1, dim> &fibre,
                  Tensor<2, dim>       &P,
                  Tensor<4, dim>       &A) const
    {
      using namespace Differentiation;
      constexpr auto number_type = AD::NumberTypes::sacado_dfad_dfad;
      using Helper               = AD::ScalarFunction<dim, number_type, double>;
      using ADNumber             = typename Helper::ad_type;
      const FEValuesExtractors::Tensor<2> F_extractor(0);

      Helper helper(Tensor<2, dim>::n_independent_components);
      helper.register_independent_variable(F, F_extractor);
      const Tensor<2, dim, ADNumber> F_ad
        = helper.get_sensitive_variables(F_extractor);
      SmallMatrix<dim, ADNumber> F_small;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          F_small[i][j] = F_ad[i][j];
      helper.register_dependent_variable(model().energy(F_small, fibre));

      Vector<double>     gradient(helper.n_independent_variables());
      FullMatrix<double> hessian(helper.n_independent_variables(),
                                 helper.n_independent_variables());
      helper.compute_gradient(gradient);
      helper.compute_hessian(hessian);
      P = helper.extract_gradient_component(gradient, F_extractor);
      A = helper.extract_hessian_component(hessian, F_extractor, F_extractor);
    }

    /// W = V Psi(C(L^2)) differentiated twice in the (dim + 1) * dim nodal
    /// coordinates with fixed-size nested Sacado numbers.
    void
    edge_length_ad(const std::vector<Tensor<1, dim>> &alpha,
                   const double                       volume,
                   const std::vector<Tensor<1, dim>> &Q,
                   const Tensor<1, dim>              &fibre,
                   double                            &energy,
                   std::vector<double>               &forces,
                   std::vector<double>               *stiffness) const
    {
      constexpr int n = (dim + 1) * dim;
      using Inner     = Sacado::Fad::SFad<double, n>;
      using Outer     = Sacado::Fad::SFad<Inner, n>;
      Outer q[dim + 1][dim];
      for (unsigned int a = 0; a <= dim; ++a)
        for (unsigned int c = 0; c < dim; ++c)
          {
            const int index = a * dim + c;
            q[a][c]         = Outer(n, index, Inner(n, index, Q[a][c]));
          }
      // Eq 26: C = -1/2 sum_{j != k} L_jk^2 alpha_j (x) alpha_k, summed over
      // the edges j < k with both orders.
      SmallMatrix<dim, Outer> C;
      for (unsigned int m = 0; m < dim; ++m)
        for (unsigned int l = 0; l < dim; ++l)
          C[m][l] = Outer(0.);
      for (unsigned int j = 0; j <= dim; ++j)
        for (unsigned int k = j + 1; k <= dim; ++k)
          {
            Outer length_squared = Outer(0.);
            for (unsigned int c = 0; c < dim; ++c)
              {
                const Outer difference = q[j][c] - q[k][c];
                length_squared += difference * difference;
              }
            for (unsigned int m = 0; m < dim; ++m)
              for (unsigned int l = 0; l < dim; ++l)
                C[m][l]
                  -= 0.5 * length_squared
                     * (alpha[j][m] * alpha[k][l] + alpha[k][m] * alpha[j][l]);
          }
      const Outer W = volume * model().energy_in_C(C, fibre);
      energy        = W.val().val();
      forces.resize(n);
      if (stiffness)
        stiffness->resize(n * n);
      for (int i = 0; i < n; ++i)
        {
          forces[i] = W.dx(i).val();
          if (stiffness)
            for (int j = 0; j < n; ++j)
              (*stiffness)[i * n + j] = W.dx(i).dx(j);
        }
    }
  };
} // namespace tissuefem::materials
