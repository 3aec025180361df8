#pragma once

#include <deal.II/lac/vector.h>

#include <tissuefem/materials/interface.h>
#include <tissuefem/solid/cell_cache.h>
#include <tissuefem/solid/discretization.h>

#include <vector>

namespace tissuefem::problems
{
  using namespace dealii;

  /**
   * The true floor of the assembly benchmark: the least arithmetic that
   * computes the compressible neo-Hookean (log J) forces, and forces with
   * tangent, of linear simplices from the same cached data the lean kernel
   * uses (shape gradients g_k, volume V and dof indices per cell), on one
   * thread, into plain arrays. With F = I + sum_k u_k (x) g_k, J = det F
   * and q_k = F^-T g_k (the spatial shape gradients),
   *
   *   f_k = V (mu F g_k + (lambda ln J - mu) q_k),
   *   K_(ka)(lb) = V (mu delta_ab g_k.g_l + lambda q_ka q_lb
   *                   + (mu - lambda ln J) q_la q_kb),
   *
   * the closed form of dP/dF (Teran's notes eq 2.8a differentiated twice)
   * contracted with the gradients by hand: about 150 flops and one log per
   * cell for the forces, 700 more for the 12 x 12 stiffness (upper half).
   * No material object, no tensor of rank four, no threads.
   */
  template <int dim>
  class NeoHookeanFloor
  {
  public:
    NeoHookeanFloor(const solid::Discretization<dim>  &discretization,
                    const materials::ElasticConstants &constants);

    /// f_int(u) into residual(), with @p jacobian the stiffness into the
    /// matrix values (entries of the sparsity of @p positions).
    void
    assemble(const Vector<double> &u, const bool jacobian);

    const Vector<double> &
    residual() const
    {
      return residual_values;
    }

  private:
    static constexpr unsigned int n_nodes = dim + 1, n = dim * (dim + 1);
    double                        lambda, mu;
    std::vector<Tensor<1, dim>>   gradients; ///< [c * n_nodes + k]
    std::vector<double>           volume;
    /// Global index of dof (node k, component a) of cell c at
    /// [c * n + k * dim + a], and where each element entry lands in the
    /// matrix values, [(c * n + i) * n + j].
    std::vector<types::global_dof_index> dofs;
    std::vector<unsigned int>            positions;
    std::vector<double>                  values;
    Vector<double>                       residual_values;
  };
} // namespace tissuefem::problems
