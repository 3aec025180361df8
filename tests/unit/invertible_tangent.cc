// The hand-coded tangent of the invertible neo-Hookean model where its
// formulas divide by differences of singular values: repeated, nearly
// repeated (gaps of 1e-6 and 1e-9), all equal, equal below and at the
// compression limit, inverted with a repeated pair, and nearly collapsed to
// a plane, a line and a point. The model is a smooth function of F at
// every one of these states (Irving, Teran and Fedkiw 2004, sec 5: the
// quotients (g_a - g_b)/(sigma_a - sigma_b) have finite limits), so the
// stress must equal the central differences of the energy, and the tangent
// those of the stress, to the differences' own accuracy. Each state is
// rotated on both sides by random rotations (fixed seeds), so that the
// singular vectors are not the axes.
//
// Not checked: states with sigma_a + sigma_b = 0 for a pair (an inverted
// element with two singular values of equal magnitude and opposite sign).
// There the model's energy has a cone-shaped ridge, it is not
// differentiable, and the tangent's (g_a + g_b)/(sigma_a + sigma_b) has no
// limit; the class clamps that denominator.

#include <deal.II/base/parameter_handler.h>

#include <tissuefem/app/parameters.h>
#include <tissuefem/materials/invertible_neo_hookean.h>

#include "../tests.h"

using namespace dealii;
using namespace tissuefem::materials;

namespace
{
  template <int dim>
  Tensor<2, dim>
  random_rotation(tissuefem_tests::Random &random)
  {
    // Cayley transform of a random skew tensor: a rotation (det +1).
    Tensor<2, dim> W;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = i + 1; j < dim; ++j)
        {
          W[i][j] = random.uniform();
          W[j][i] = -W[i][j];
        }
    const Tensor<2, dim> I = unit_symmetric_tensor<dim>();
    return invert(I - W) * (I + W);
  }


  /// Largest relative errors of the stress against the energy's central
  /// differences and of the tangent against the stress's.
  template <int dim>
  std::pair<double, double>
  errors(const InvertibleNeoHookean<dim> &model, const Tensor<2, dim> &F)
  {
    const Tensor<1, dim> fibre;
    Tensor<2, dim>       P;
    Tensor<4, dim>       A;
    model.stress_and_tangent(F, fibre, P, A, TangentMethod::hand_coded);
    // Steps small against the smallest singular value (the scale on which
    // P varies), large against round-off: the stress comes from singular
    // values found through F^T F, with relative round-off up to about 1e-10
    // where sigma_min / sigma_max = 1e-3, which the difference quotient
    // divides by the step.
    double smallest = 1e300;
    {
      Tensor<2, dim>          U, V;
      std::array<double, dim> sigma;
      InvertibleNeoHookean<dim>::signed_svd(F, U, sigma, V);
      for (const double s : sigma)
        smallest = std::min(smallest, std::abs(s));
    }
    const double   h = 1e-5 * std::max(smallest, 1e-3);
    Tensor<2, dim> dP_energy;
    Tensor<4, dim> dA_stress;
    for (unsigned int k = 0; k < dim; ++k)
      for (unsigned int l = 0; l < dim; ++l)
        {
          Tensor<2, dim> plus = F, minus = F;
          plus[k][l] += h;
          minus[k][l] -= h;
          dP_energy[k][l] = (model.energy_density(plus, fibre)
                             - model.energy_density(minus, fibre))
                            / (2 * h);
          const Tensor<2, dim> dP
            = (model.stress(plus, fibre) - model.stress(minus, fibre))
              / (2 * h);
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = 0; j < dim; ++j)
              dA_stress[i][j][k][l] = dP[i][j];
        }
    return {(P - dP_energy).norm() / P.norm(),
            (A - dA_stress).norm() / A.norm()};
  }


  template <int dim>
  void
  check_states(const ParameterHandler &prm)
  {
    const auto constants = ElasticConstants::from_young_poisson(1000, 0.3);
    const InvertibleNeoHookean<dim> model(constants, prm);
    // Singular values in 2D and in 3D; an empty 2D list: no 2D analogue
    // (a repeated pair with an inverted third lies on the ridge
    // sigma_1 + sigma_2 = 0 in 2D).
    struct State
    {
      std::string           name;
      std::vector<double>   in_2d;
      std::array<double, 3> in_3d;
    };
    const std::vector<State> states
      = {{"distinct", {1.3, 0.6}, {{1.3, 0.9, 0.6}}},
         {"two equal", {1.2, 1.2}, {{1.2, 1.2, 0.8}}},
         {"all equal", {0.9, 0.9}, {{0.9, 0.9, 0.9}}},
         {"gap 1e-6", {1.1 + 1e-6, 1.1}, {{1.1 + 1e-6, 1.1, 0.7}}},
         {"gap 1e-9", {1.1 + 1e-9, 1.1}, {{1.1 + 1e-9, 1.1, 0.7}}},
         {"equal below the compression limit", {0.3, 0.3}, {{0.3, 0.3, 0.2}}},
         {"equal at the compression limit", {0.5, 0.5}, {{0.5, 0.5, 0.5}}},
         {"inverted", {1.1, -0.4}, {{1.1, 0.6, -0.4}}},
         {"inverted, a repeated pair", {}, {{0.8, 0.8, -0.3}}},
         {"nearly a line (2D) or plane (3D)", {1., 1e-3}, {{1., 1., 1e-3}}},
         {"nearly a line (3D)", {}, {{1., 1e-3, 1e-3}}},
         {"nearly a point", {1e-3, 1e-3}, {{1e-3, 1e-3, 1e-3}}}};
    tissuefem_tests::Random random(17 + dim);
    for (const auto &[name, in_2d, in_3d] : states)
      {
        if (dim == 2 && in_2d.empty())
          continue;
        double worst_stress = 0, worst_tangent = 0;
        for (unsigned int sample = 0; sample < 5; ++sample)
          {
            Tensor<2, dim> D;
            for (unsigned int i = 0; i < dim; ++i)
              D[i][i] = dim == 2 ? in_2d[i] : in_3d[i];
            const Tensor<2, dim> F
              = random_rotation<dim>(random) * D * random_rotation<dim>(random);
            const auto [stress, tangent] = errors(model, F);
            tissuefem_tests::raise(worst_stress, stress);
            tissuefem_tests::raise(worst_tangent, tangent);
          }
        const std::string label = std::to_string(dim) + "D, " + name;
        tissuefem_tests::check_small(worst_stress,
                                     1e-6,
                                     label
                                       + ": stress against the energy's "
                                         "differences (relative)");
        // 2e-5: at the compression limit the third derivative of l jumps,
        // so the central differences of the stress err by O(h) there
        // (measured 3e-6), and nearly a line the stress's round-off over
        // the step gives 6e-6. A tangent formula wrong at repeated values
        // errs by O(1).
        tissuefem_tests::check_small(worst_tangent,
                                     2e-5,
                                     label
                                       + ": tangent against the stress's "
                                         "differences (relative)");
      }
  }
} // namespace


int
main()
{
  ParameterHandler prm;
  tissuefem::declare_all_parameters(prm);
  check_states<2>(prm);
  check_states<3>(prm);
  return tissuefem_tests::exit_status();
}
