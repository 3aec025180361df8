#pragma once

#include <deal.II/differentiation/ad.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/materials/interface.h>
#include <tissuefem/materials/small_matrix.h>

#include <Sacado.hpp>

namespace tissuefem::materials
{
  /**
   * Turns an energy density into a material: @p Model writes
   *
   *   template <typename Number>
   *   Number energy(const SmallMatrix<dim, Number> &F) const;
   *
   * once, and this class differentiates it. The default path seeds the d*d
   * entries of F as fixed-size forward AD numbers nested twice, so one energy
   * evaluation yields Psi, P and dP/dF exactly, with all storage on the stack.
   * The alternative path uses deal.II's ScalarFunction helper (dynamic
   * Sacado numbers), which is slower but is what deal.II documents.
   */
  template <int dim, typename Model>
  class EnergyMaterial : public Interface<dim>
  {
  public:
    static constexpr int n_entries = dim * dim;
    using FirstOrder               = Sacado::Fad::SFad<double, n_entries>;
    using SecondOrder              = Sacado::Fad::SFad<FirstOrder, n_entries>;

    double
    energy_density(const Tensor<2, dim> &F) const override
    {
      SmallMatrix<dim, double> F_small;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          F_small[i][j] = F[i][j];
      return model().energy(F_small);
    }

    Tensor<2, dim>
    stress(const Tensor<2, dim> &F) const override
    {
      SmallMatrix<dim, FirstOrder> F_ad;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          F_ad[i][j] = FirstOrder(n_entries, i * dim + j, F[i][j]);
      const FirstOrder psi = model().energy(F_ad);
      Tensor<2, dim>   P;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          P[i][j] = psi.dx(i * dim + j);
      return P;
    }

    void
    stress_and_tangent(const Tensor<2, dim> &F,
                       Tensor<2, dim>       &P,
                       Tensor<4, dim>       &A,
                       const TangentMethod   method) const override
    {
      switch (method)
        {
          case TangentMethod::automatic_differentiation:
            fixed_size_ad(F, P, A);
            return;
          case TangentMethod::dealii_ad_helper:
            dealii_helper(F, P, A);
            return;
          case TangentMethod::hand_coded:
            hand_coded_stress_and_tangent(F, P, A);
            return;
        }
    }

  protected:
    /// Materials with a closed-form tangent override this and
    /// has_hand_coded_tangent().
    virtual void
    hand_coded_stress_and_tangent(const Tensor<2, dim> &,
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

    void
    fixed_size_ad(const Tensor<2, dim> &F,
                  Tensor<2, dim>       &P,
                  Tensor<4, dim>       &A) const
    {
      SmallMatrix<dim, SecondOrder> F_ad;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          {
            const int index = i * dim + j;
            F_ad[i][j] =
              SecondOrder(n_entries, index, FirstOrder(n_entries, index, F[i][j]));
          }
      const SecondOrder psi = model().energy(F_ad);
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
                  Tensor<2, dim>       &P,
                  Tensor<4, dim>       &A) const
    {
      using namespace Differentiation;
      constexpr auto number_type = AD::NumberTypes::sacado_dfad_dfad;
      using Helper = AD::ScalarFunction<dim, number_type, double>;
      using ADNumber                     = typename Helper::ad_type;
      const FEValuesExtractors::Tensor<2> F_extractor(0);

      Helper helper(Tensor<2, dim>::n_independent_components);
      helper.register_independent_variable(F, F_extractor);
      const Tensor<2, dim, ADNumber> F_ad =
        helper.get_sensitive_variables(F_extractor);
      SmallMatrix<dim, ADNumber> F_small;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          F_small[i][j] = F_ad[i][j];
      helper.register_dependent_variable(model().energy(F_small));

      Vector<double>     gradient(helper.n_independent_variables());
      FullMatrix<double> hessian(helper.n_independent_variables(),
                                 helper.n_independent_variables());
      helper.compute_gradient(gradient);
      helper.compute_hessian(hessian);
      P = helper.extract_gradient_component(gradient, F_extractor);
      A = helper.extract_hessian_component(hessian, F_extractor, F_extractor);
    }
  };
} // namespace tissuefem::materials
