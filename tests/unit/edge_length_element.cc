// Jeffrey's edge-length formulation (eqs 19-31) against the displacement
// formulation, for every model written in C = F^T F, on random triangles and
// tetrahedra under random (large, also inverting) deformations:
// - element energy V Psi(F) against W(L^2) of the edge-length element;
// - nodal forces f_(a,c) = V P_cj alpha_a,j against dW/dQ;
// - stiffness V A_cjdl alpha_a,j alpha_b,l against d2W/dQ2;
// all to round-off, relative to the largest entry. Also checks that a rigid
// rotation and translation of the deformed element leaves energy zero and
// forces zero (the point of the formulation).

#include <deal.II/base/parameter_handler.h>

#include <tissuefem/app/parameters.h>
#include <tissuefem/materials/material_set.h>

#include "../tests.h"

using namespace dealii;
using namespace tissuefem::materials;

namespace
{
  template <int dim>
  Tensor<1, dim>
  random_vector(tissuefem_tests::Random &random, const double scale)
  {
    Tensor<1, dim> v;
    for (unsigned int d = 0; d < dim; ++d)
      v[d] = scale * random.uniform();
    return v;
  }

  template <int dim>
  void
  check_model(const std::string &name, const Interface<dim> &model)
  {
    tissuefem_tests::Random random(42);
    Tensor<1, dim>          fibre = random_vector<dim>(random, 1.);
    fibre /= fibre.norm();
    double energy_error = 0, force_error = 0, stiffness_error = 0,
           rigid_force = 0;
    for (unsigned int sample = 0; sample < 20; ++sample)
      {
        // A random simplex X_0..X_d and its barycentric gradients alpha.
        std::vector<Tensor<1, dim>> X(dim + 1), alpha(dim + 1), Q(dim + 1);
        Tensor<2, dim>              D;
        do
          {
            for (auto &x : X)
              x = random_vector<dim>(random, 1.);
            for (unsigned int a = 1; a <= dim; ++a)
              for (unsigned int d = 0; d < dim; ++d)
                D[d][a - 1] = X[a][d] - X[0][d];
          }
        while (std::abs(determinant(D)) < 0.05);
        const Tensor<2, dim> D_inverse = invert(D);
        alpha[0]                       = 0;
        for (unsigned int a = 1; a <= dim; ++a)
          {
            alpha[a] = D_inverse[a - 1];
            alpha[0] -= alpha[a];
          }
        double volume = std::abs(determinant(D));
        for (unsigned int k = 2; k <= dim; ++k)
          volume /= k;

        // A random deformation of the nodes, and its F = I + sum u_a (x)
        // alpha_a.
        Tensor<2, dim> F = unit_symmetric_tensor<dim>();
        for (unsigned int a = 0; a <= dim; ++a)
          {
            const Tensor<1, dim> u = random_vector<dim>(random, 0.4);
            Q[a]                   = X[a] + u;
            F += outer_product(u, alpha[a]);
          }

        Tensor<2, dim> P;
        Tensor<4, dim> A;
        model.stress_and_tangent(
          F, fibre, P, A, TangentMethod::automatic_differentiation);
        const double        W = volume * model.energy_density(F, fibre);
        double              W_edge;
        std::vector<double> forces, stiffness;
        model.edge_length_element(
          alpha, volume, Q, fibre, W_edge, forces, &stiffness);

        const unsigned int  n           = (dim + 1) * dim;
        double              force_scale = 1e-300, stiffness_scale = 1e-300;
        std::vector<double> f(n), K(n * n);
        for (unsigned int a = 0; a <= dim; ++a)
          for (unsigned int c = 0; c < dim; ++c)
            {
              f[a * dim + c] = volume * (P[c] * alpha[a]);
              for (unsigned int b = 0; b <= dim; ++b)
                for (unsigned int e = 0; e < dim; ++e)
                  {
                    double value = 0;
                    for (unsigned int j = 0; j < dim; ++j)
                      for (unsigned int l = 0; l < dim; ++l)
                        value += A[c][j][e][l] * alpha[a][j] * alpha[b][l];
                    K[(a * dim + c) * n + b * dim + e] = volume * value;
                  }
            }
        for (unsigned int i = 0; i < n; ++i)
          {
            tissuefem_tests::raise(force_scale, std::abs(f[i]));
            for (unsigned int j = 0; j < n; ++j)
              tissuefem_tests::raise(stiffness_scale, std::abs(K[i * n + j]));
          }
        tissuefem_tests::raise(energy_error,
                               std::abs(W - W_edge) / std::abs(W));
        for (unsigned int i = 0; i < n; ++i)
          {
            tissuefem_tests::raise(force_error,
                                   std::abs(f[i] - forces[i]) / force_scale);
            for (unsigned int j = 0; j < n; ++j)
              tissuefem_tests::raise(stiffness_error,
                                     std::abs(K[i * n + j]
                                              - stiffness[i * n + j])
                                       / stiffness_scale);
          }

        // A rigid motion of the undeformed simplex: no energy, no force.
        Tensor<2, dim> W0;
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            W0[i][j] = random.uniform();
        const Tensor<2, dim> skew  = W0 - transpose(W0);
        const Tensor<2, dim> I     = unit_symmetric_tensor<dim>();
        const Tensor<2, dim> R     = invert(I - skew) * (I + skew);
        const Tensor<1, dim> shift = random_vector<dim>(random, 5.);
        for (unsigned int a = 0; a <= dim; ++a)
          Q[a] = R * X[a] + shift;
        model.edge_length_element(
          alpha, volume, Q, fibre, W_edge, forces, nullptr);
        for (const double value : forces)
          tissuefem_tests::raise(rigid_force, std::abs(value) / force_scale);
      }
    const std::string prefix
      = std::to_string(dim) + "D " + name + ": edge length vs displacement";
    tissuefem_tests::check_small(energy_error,
                                 1e-12,
                                 prefix + ", energy (relative)");
    tissuefem_tests::check_small(force_error,
                                 1e-12,
                                 prefix + ", nodal forces (relative)");
    tissuefem_tests::check_small(stiffness_error,
                                 1e-12,
                                 prefix + ", stiffness (relative)");
    tissuefem_tests::check_small(
      rigid_force, 1e-12, prefix + ", forces under rigid motion (relative)");
  }

  template <int dim>
  void
  check_all(const ParameterHandler &prm)
  {
    const auto constants = ElasticConstants::from_young_poisson(20000, 0.4);
    tissuefem_tests::EachModel each(std::to_string(dim) + "D",
                                    "each registered model with an edge-length "
                                    "form");
    for (const auto &[name, entry] : MaterialRegistry<dim>::instance().all())
      {
        each.model(name);
        const auto model = entry.create(constants, prm);
        if (model->has_edge_length_form())
          check_model<dim>(name, *model);
      }
  }
} // namespace


int
main()
{
  ParameterHandler prm;
  tissuefem::declare_all_parameters(prm);
  prm.parse_input_from_string(R"(
    subsection Materials
      subsection Transversely isotropic St Venant-Kirchhoff
        set Young's modulus along fibre = 150000
      end
    end)");
  check_all<2>(prm);
  check_all<3>(prm);
  return tissuefem_tests::exit_status();
}
