// Every registered material, in 1, 2 and 3 dimensions, against its own
// energy (the checks of 'tissuefem --check-material'): P(I) = 0, AD stress
// against central differences of the energy, AD tangent against central
// differences of the stress, Taylor remainders decaying like h^2, all
// tangent methods agreeing, major symmetry, frame indifference (all but
// linear elasticity); inverted F is sampled for the models that admit it.
// Then, in 2D, the AD tangent of the robust neo-Hookean model against the
// problem session's hand-derived eq 20 as its Matlab eval_dq_du builds it,
// corrected as errata T6 and T7 (doc/references.md) say.

#include <deal.II/base/parameter_handler.h>

#include <tissuefem/app/parameters.h>
#include <tissuefem/materials/consistency_check.h>
#include <tissuefem/materials/material_set.h>

#include "../tests.h"

using namespace dealii;
using namespace tissuefem::materials;

namespace
{
  const ElasticConstants constants
    = ElasticConstants::from_young_poisson(1000, 0.3);

  template <int dim>
  void
  check_all_models(const ParameterHandler &prm)
  {
    tissuefem_tests::EachModel each(std::to_string(dim) + "D");
    for (const auto &[name, entry] : MaterialRegistry<dim>::instance().all())
      {
        each.model(name);
        const auto model  = entry.create(constants, prm);
        const auto report = check_consistency<dim>(name, *model, constants.mu);
        tissuefem_tests::check(report.passes(),
                               std::to_string(dim) + "D " + name
                                 + ": consistent with its energy",
                               "(see tissuefem --check-material)");
        if (!report.passes())
          print_consistency_table(std::cout, {report});
      }
  }

  /// dP_ik/dF_jm as the problem session's eval_dq_du assembles it for the
  /// robust neo-Hookean model (eq 20), with errata T6 and T7
  /// (doc/references.md) applied: the c1 term is the outer product of rows i
  /// and j of dJ/dF, and mu is added to both diagonal entries when i == j,
  /// after the assignment.
  Tensor<4, 2>
  problem_session_tangent(const Tensor<2, 2> &F)
  {
    const double mu = constants.mu, lambda = constants.lambda;
    const double J           = F[0][0] * F[1][1] - F[0][1] * F[1][0];
    const double dJ_dF[2][2] = {{F[1][1], -F[1][0]}, {-F[0][1], F[0][0]}};
    const double x           = J - 1;
    const double rJ          = x - x * x / 2 + x * x * x / 3;
    const double drJ         = 1 - x + x * x;
    const double d2rJ        = -1 + 2 * x;
    const double c1          = lambda * drJ * drJ + (lambda * rJ - mu) * d2rJ;
    const double c2          = (lambda * rJ - mu) * drJ;
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
} // namespace


int
main()
{
  ParameterHandler prm;
  tissuefem::declare_all_parameters(prm);
  check_all_models<1>(prm);
  check_all_models<2>(prm);
  check_all_models<3>(prm);

  const auto robust
    = MaterialRegistry<2>::instance().create("robust neo-Hookean",
                                             constants,
                                             prm);
  tissuefem_tests::Random random(7);
  Tensor<1, 2>            fibre({1., 0.});
  double                  difference = 0;
  for (unsigned int sample = 0; sample < 20; ++sample)
    {
      Tensor<2, 2> F;
      for (unsigned int i = 0; i < 2; ++i)
        for (unsigned int j = 0; j < 2; ++j)
          F[i][j] = (i == j) + 0.3 * random.uniform();
      if (sample % 2 == 1)
        F[0] *= -1.; // inverted
      Tensor<2, 2> P;
      Tensor<4, 2> A;
      robust->stress_and_tangent(
        F, fibre, P, A, TangentMethod::automatic_differentiation_in_F);
      const Tensor<4, 2> teran = problem_session_tangent(F);
      for (unsigned int i = 0; i < 2; ++i)
        for (unsigned int k = 0; k < 2; ++k)
          for (unsigned int j = 0; j < 2; ++j)
            for (unsigned int m = 0; m < 2; ++m)
              tissuefem_tests::raise(difference,
                                     std::abs(teran[i][k][j][m] - A[i][k][j][m])
                                       / constants.mu);
    }
  tissuefem_tests::check_small(difference,
                               1e-12,
                               "2D robust neo-Hookean: AD tangent vs problem "
                               "session eq 20 (relative to mu)");
  return tissuefem_tests::exit_status();
}
