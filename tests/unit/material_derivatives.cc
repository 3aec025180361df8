// Checks the derivatives of every material model against its energy, in 1, 2
// and 3 dimensions, at random deformation gradients (inverted ones too for
// the models that admit inversion):
// - the AD stress equals central differences of the energy;
// - the AD tangent equals central differences of the AD stress;
// - Taylor tests: |Psi(F + h dF) - Psi(F) - h P:dF| and
//   |P(F + h dF) - P(F) - h A:dF| decay like h^2;
// - every tangent method gives the same P and A to round-off;
// - the tangent has major symmetry A_ijkl = A_klij;
// - P(I) = 0;
// - in 2D, the tangent equals the problem session's hand-derived eq 20 as
//   its Matlab eval_dq_du builds it, corrected as ERRATA items 6-7 say.

#include <deal.II/base/parameter_handler.h>

#include <tissuefem/materials/interface.h>
#include <tissuefem/materials/material_set.h>

#include "../tests.h"

using namespace dealii;
using namespace tissuefem::materials;
using tissuefem_tests::check;
using tissuefem_tests::check_small;

namespace
{
  const ElasticConstants constants = ElasticConstants::from_young_poisson(1000, 0.3);

  template <int dim>
  Tensor<2, dim>
  random_tensor(tissuefem_tests::Random &random, const double scale)
  {
    Tensor<2, dim> T;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        T[i][j] = scale * random.uniform();
    return T;
  }

  /// A random deformation gradient with det F of the requested sign.
  template <int dim>
  Tensor<2, dim>
  random_F(tissuefem_tests::Random &random, const bool inverted)
  {
    Tensor<2, dim> F = unit_symmetric_tensor<dim>() + random_tensor<dim>(random, 0.3);
    if (inverted)
      F[0] *= -1.;
    return F;
  }

  template <int dim>
  double
  max_abs(const Tensor<2, dim> &T)
  {
    double m = 0;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        m = std::max(m, std::abs(T[i][j]));
    return m;
  }

  /// The 2D tangent as the problem session's eval_dq_du assembles it for the
  /// robust neo-Hookean model (eq 20), with ERRATA items 6 and 7 applied:
  /// the c1 term is the outer product of rows i and j of dJ/dF, and mu is
  /// added to both diagonal entries when i == j, after the assignment.
  /// Returns dP_ik/dF_jm.
  Tensor<4, 2>
  teran_problem_session_tangent(const Tensor<2, 2> &F, const double mu, const double lambda)
  {
    const double J = F[0][0] * F[1][1] - F[0][1] * F[1][0];
    const double dJ_dF[2][2] = {{F[1][1], -F[1][0]}, {-F[0][1], F[0][0]}};
    const double x    = J - 1;
    const double rJ   = x - x * x / 2 + x * x * x / 3;
    const double drJ  = 1 - x + x * x;
    const double d2rJ = -1 + 2 * x;
    const double c1   = lambda * drJ * drJ + (lambda * rJ - mu) * d2rJ;
    const double c2   = (lambda * rJ - mu) * drJ;
    Tensor<4, 2> result;
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int j = 0; j < 2; ++j)
        {
          double block[2][2];
          for (unsigned int k = 0; k < 2; ++k)
            for (unsigned int m = 0; m < 2; ++m)
              block[k][m] = c1 * dJ_dF[i][k] * dJ_dF[j][m];
          if (i == j)
            for (unsigned int k = 0; k < 2; ++k)
              block[k][k] += mu;
          if (i != j)
            {
              block[i][j] += c2;
              block[j][i] -= c2;
            }
          for (unsigned int k = 0; k < 2; ++k)
            for (unsigned int m = 0; m < 2; ++m)
              result[i][k][j][m] = block[k][m];
        }
    return result;
  }


  template <int dim>
  void
  check_model(const std::string &name, tissuefem_tests::Random &random)
  {
    ParameterHandler prm;
    const auto model = MaterialRegistry<dim>::instance().create(name, constants, prm);
    const std::string prefix = std::to_string(dim) + "D " + name;

    check_small(max_abs(model->stress(unit_symmetric_tensor<dim>())) / constants.mu,
                1e-12,
                prefix + ": P(I) / mu");

    std::vector<TangentMethod> methods = {TangentMethod::automatic_differentiation,
                                          TangentMethod::automatic_differentiation_in_F,
                                          TangentMethod::dealii_ad_helper};
    if (model->has_hand_coded_tangent())
      methods.push_back(TangentMethod::hand_coded);

    double stress_fd = 0, tangent_fd = 0, method_spread = 0, asymmetry = 0;
    double worst_energy_slope = 10, worst_stress_slope = 10;
    for (unsigned int sample = 0; sample < 20; ++sample)
      {
        const bool inverted = model->admits_inversion() && sample % 2 == 1;
        const Tensor<2, dim> F = random_F<dim>(random, inverted);
        Tensor<2, dim> P;
        Tensor<4, dim> A;
        model->stress_and_tangent(F, P, A, TangentMethod::automatic_differentiation);
        const double scale = std::max(max_abs(P), constants.mu);

        // Central differences, step h = 1e-6 in every entry of F.
        const double h = 1e-6;
        for (unsigned int k = 0; k < dim; ++k)
          for (unsigned int l = 0; l < dim; ++l)
            {
              Tensor<2, dim> Fp = F, Fm = F;
              Fp[k][l] += h;
              Fm[k][l] -= h;
              const double dpsi = (model->energy_density(Fp) - model->energy_density(Fm)) / (2 * h);
              stress_fd = std::max(stress_fd, std::abs(dpsi - P[k][l]) / scale);
              const Tensor<2, dim> dP = (model->stress(Fp) - model->stress(Fm)) / (2 * h);
              for (unsigned int i = 0; i < dim; ++i)
                for (unsigned int j = 0; j < dim; ++j)
                  tangent_fd = std::max(tangent_fd, std::abs(dP[i][j] - A[i][j][k][l]) / scale);
            }

        for (const auto method : methods)
          {
            Tensor<2, dim> P2;
            Tensor<4, dim> A2;
            model->stress_and_tangent(F, P2, A2, method);
            method_spread = std::max(method_spread, max_abs(P2 - P) / scale);
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = 0; j < dim; ++j)
                for (unsigned int k = 0; k < dim; ++k)
                  for (unsigned int l = 0; l < dim; ++l)
                    {
                      method_spread = std::max(method_spread, std::abs(A2[i][j][k][l] - A[i][j][k][l]) / scale);
                      asymmetry = std::max(asymmetry, std::abs(A[i][j][k][l] - A[k][l][i][j]) / scale);
                    }
          }

        // Taylor test: remainders at h and h/2 for a random direction.
        const Tensor<2, dim> dF = random_tensor<dim>(random, 1.0);
        auto remainders = [&](const double step, double &energy_rest, double &stress_rest) {
          const Tensor<2, dim> Fh = F + step * dF;
          energy_rest = std::abs(model->energy_density(Fh) - model->energy_density(F) - step * scalar_product(P, dF));
          stress_rest = max_abs(model->stress(Fh) - P - step * double_contract<2, 0, 3, 1>(A, dF));
        };
        double e1, s1, e2, s2;
        remainders(1e-3, e1, s1);
        remainders(5e-4, e2, s2);
        worst_energy_slope = std::min(worst_energy_slope, std::log2(e1 / e2));
        worst_stress_slope = std::min(worst_stress_slope, std::log2(s1 / s2));
      }
    check_small(stress_fd, 1e-6, prefix + ": AD stress vs finite differences of energy (relative)");
    check_small(tangent_fd, 1e-6, prefix + ": AD tangent vs finite differences of stress (relative)");
    check_small(method_spread, 1e-12, prefix + ": all tangent methods agree (relative)");
    check_small(asymmetry, 1e-12, prefix + ": major symmetry of the tangent (relative)");
    check(worst_energy_slope > 1.9 && worst_energy_slope < 2.1,
          prefix + ": energy Taylor remainder decays like h^2",
          "slope " + std::to_string(worst_energy_slope));
    check(worst_stress_slope > 1.9 && worst_stress_slope < 2.1,
          prefix + ": stress Taylor remainder decays like h^2",
          "slope " + std::to_string(worst_stress_slope));
  }
} // namespace


int
main()
{
  tissuefem_tests::Random random(20261122);
  for (const std::string name : {"neo-Hookean", "robust neo-Hookean"})
    {
      check_model<1>(name, random);
      check_model<2>(name, random);
      check_model<3>(name, random);
    }

  // The problem session's hand-derived tangent (eq 20) against AD.
  ParameterHandler prm;
  const auto robust = MaterialRegistry<2>::instance().create("robust neo-Hookean", constants, prm);
  double difference = 0;
  for (unsigned int sample = 0; sample < 20; ++sample)
    {
      const Tensor<2, 2> F = random_F<2>(random, sample % 2 == 1);
      Tensor<2, 2> P;
      Tensor<4, 2> A;
      robust->stress_and_tangent(F, P, A, TangentMethod::automatic_differentiation_in_F);
      const Tensor<4, 2> teran = teran_problem_session_tangent(F, constants.mu, constants.lambda);
      // teran[i][k][j][m] = dP_ik/dF_jm = A[i][k][j][m].
      for (unsigned int i = 0; i < 2; ++i)
        for (unsigned int k = 0; k < 2; ++k)
          for (unsigned int j = 0; j < 2; ++j)
            for (unsigned int m = 0; m < 2; ++m)
              difference = std::max(difference, std::abs(teran[i][k][j][m] - A[i][k][j][m]) / constants.mu);
    }
  check_small(difference, 1e-12, "2D robust neo-Hookean: AD tangent vs problem session eq 20 (relative to mu)");
  return tissuefem_tests::exit_status();
}
