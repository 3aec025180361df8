#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <tissuefem/problems/floor_kernel.h>

namespace tissuefem::problems
{
  template <int dim>
  FloorKernel<dim>::FloorKernel(
    const solid::Discretization<dim>  &discretization,
    const materials::MaterialSet<dim> &materials)
      : materials(materials)
  {
    cache.build(discretization, false);
    fibres.build(discretization, materials, false);
    DynamicSparsityPattern dsp(discretization.n_dofs());
    DoFTools::make_sparsity_pattern(discretization.dof_handler, dsp);
    sparsity.copy_from(dsp);
    values.assign(sparsity.n_nonzero_elements(), 0.);
    residual_values.reinit(discretization.n_dofs());
    const unsigned int n = cache.n_dofs;
    positions.resize(cache.cells().size() * n * n);
    for (unsigned int c = 0; c < cache.cells().size(); ++c)
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = 0; j < n; ++j)
          positions[(c * n + i) * n + j]
            = sparsity(cache.dofs(c)[i], cache.dofs(c)[j]);
  }


  template <int dim>
  void
  FloorKernel<dim>::assemble(const Vector<double> &u, const bool jacobian)
  {
    const unsigned int n = cache.n_dofs, n_q = cache.n_q;
    const unsigned int n_scalar = cache.n_scalar;
    const auto         method   = materials.tangent_method();
    residual_values             = 0;
    if (jacobian)
      std::fill(values.begin(), values.end(), 0.);
    std::vector<Tensor<1, dim>> U(n_scalar);
    std::vector<double>         cell_rhs(n), cell_matrix(n * n);
    Tensor<2, dim>              P;
    Tensor<4, dim>              A;
    Tensor<3, dim>              B;
    for (unsigned int c = 0; c < cache.cells().size(); ++c)
      {
        const auto *dofs     = cache.dofs(c);
        const auto &cell     = cache.cells()[c];
        const auto &material = materials.material(cell->material_id());
        for (unsigned int k = 0; k < n_scalar; ++k)
          for (unsigned int a = 0; a < dim; ++a)
            U[k][a] = u[dofs[cache.local_index[k * dim + a]]];
        std::fill(cell_rhs.begin(), cell_rhs.end(), 0.);
        if (jacobian)
          std::fill(cell_matrix.begin(), cell_matrix.end(), 0.);
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const double   JxW = cache.JxW(c)[q];
            Tensor<2, dim> F   = unit_symmetric_tensor<dim>();
            for (unsigned int k = 0; k < n_scalar; ++k)
              F += outer_product(U[k], cache.gradient(c, q, k));
            const Tensor<1, dim> &fibre
              = fibres.at(cell->active_cell_index(), q);
            if (jacobian)
              material.stress_and_tangent(F, fibre, P, A, method);
            else
              P = material.stress(F, fibre);
            for (unsigned int k = 0; k < n_scalar; ++k)
              {
                const Tensor<1, dim> &g_k = cache.gradient(c, q, k);
                const Tensor<1, dim>  r   = P * g_k;
                for (unsigned int a = 0; a < dim; ++a)
                  cell_rhs[cache.local_index[k * dim + a]] += r[a] * JxW;
                if (!jacobian)
                  continue;
                for (unsigned int a = 0; a < dim; ++a)
                  {
                    B[a] = 0;
                    for (unsigned int m = 0; m < dim; ++m)
                      B[a] += g_k[m] * A[a][m];
                  }
                for (unsigned int l = 0; l < n_scalar; ++l)
                  {
                    const Tensor<1, dim> &g_l = cache.gradient(c, q, l);
                    for (unsigned int a = 0; a < dim; ++a)
                      for (unsigned int b = 0; b < dim; ++b)
                        cell_matrix[cache.local_index[k * dim + a] * n
                                    + cache.local_index[l * dim + b]]
                          += (B[a][b] * g_l) * JxW;
                  }
              }
          }
        for (unsigned int i = 0; i < n; ++i)
          residual_values[dofs[i]] += cell_rhs[i];
        if (jacobian)
          {
            const std::size_t *position = &positions[c * n * n];
            for (unsigned int ij = 0; ij < n * n; ++ij)
              values[position[ij]] += cell_matrix[ij];
          }
      }
  }

  template class FloorKernel<1>;
  template class FloorKernel<2>;
  template class FloorKernel<3>;
} // namespace tissuefem::problems
