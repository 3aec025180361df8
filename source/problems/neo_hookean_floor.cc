#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <tissuefem/problems/neo_hookean_floor.h>

#include <cmath>

namespace tissuefem::problems
{
  template <int dim>
  NeoHookeanFloor<dim>::NeoHookeanFloor(
    const solid::Discretization<dim>  &discretization,
    const materials::ElasticConstants &constants)
      : lambda(constants.lambda)
      , mu(constants.mu)
  {
    solid::CellCache<dim> cache;
    cache.build(discretization, false);
    AssertThrow(cache.n_scalar == n_nodes && cache.n_dofs == n,
                ExcMessage("the neo-Hookean floor needs linear simplices"));
    DynamicSparsityPattern dsp(discretization.n_dofs());
    DoFTools::make_sparsity_pattern(discretization.dof_handler, dsp);
    SparsityPattern sparsity;
    sparsity.copy_from(dsp);
    values.assign(sparsity.n_nonzero_elements(), 0.);
    residual_values.reinit(discretization.n_dofs());
    const unsigned int n_cells = cache.cells().size();
    gradients.resize(n_cells * n_nodes);
    volume.resize(n_cells);
    dofs.resize(n_cells * n);
    positions.resize(n_cells * n * n);
    for (unsigned int c = 0; c < n_cells; ++c)
      {
        volume[c] = 0;
        for (unsigned int q = 0; q < cache.n_q; ++q)
          volume[c] += cache.JxW(c)[q];
        for (unsigned int k = 0; k < n_nodes; ++k)
          {
            gradients[c * n_nodes + k] = cache.gradient(c, 0, k);
            for (unsigned int a = 0; a < dim; ++a)
              dofs[c * n + k * dim + a]
                = cache.dofs(c)[cache.local_index[k * dim + a]];
          }
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j < n; ++j)
            positions[(c * n + i) * n + j]
              = sparsity(dofs[c * n + i], dofs[c * n + j]);
      }
  }


  template <int dim>
  void
  NeoHookeanFloor<dim>::assemble(const Vector<double> &u, const bool jacobian)
  {
    residual_values = 0;
    if (jacobian)
      std::fill(values.begin(), values.end(), 0.);
    const unsigned int n_cells = volume.size();
    for (unsigned int c = 0; c < n_cells; ++c)
      {
        const Tensor<1, dim>          *g = &gradients[c * n_nodes];
        const types::global_dof_index *d = &dofs[c * n];
        Tensor<2, dim>                 F = unit_symmetric_tensor<dim>();
        for (unsigned int k = 0; k < n_nodes; ++k)
          for (unsigned int a = 0; a < dim; ++a)
            F[a] += u[d[k * dim + a]] * g[k];
        const double         J          = determinant(F);
        const Tensor<2, dim> inverse    = invert(F);
        const double         log_J      = std::log(J);
        const double         V          = volume[c];
        const double         volumetric = lambda * log_J - mu;
        Tensor<1, dim>       q[n_nodes];
        for (unsigned int k = 0; k < n_nodes; ++k)
          {
            // q_k = F^-T g_k
            q[k]                   = transpose(inverse) * g[k];
            const Tensor<1, dim> f = V * (mu * (F * g[k]) + volumetric * q[k]);
            for (unsigned int a = 0; a < dim; ++a)
              residual_values[d[k * dim + a]] += f[a];
          }
        if (!jacobian)
          continue;
        // Node blocks l >= k, each added at (k, l) and mirrored to (l, k).
        const unsigned int *position = &positions[c * n * n];
        const double        Vl = V * lambda, Vv = V * volumetric;
        for (unsigned int k = 0; k < n_nodes; ++k)
          for (unsigned int l = k; l < n_nodes; ++l)
            {
              const double gg = V * mu * (g[k] * g[l]);
              for (unsigned int a = 0; a < dim; ++a)
                for (unsigned int b = 0; b < dim; ++b)
                  {
                    const double value = (a == b ? gg : 0.)
                                         + Vl * q[k][a] * q[l][b]
                                         - Vv * q[l][a] * q[k][b];
                    values[position[(k * dim + a) * n + l * dim + b]] += value;
                    if (l != k)
                      values[position[(l * dim + b) * n + k * dim + a]]
                        += value;
                  }
            }
      }
  }

  template class NeoHookeanFloor<2>;
  template class NeoHookeanFloor<3>;
} // namespace tissuefem::problems
