// NodalDilatationSystem's cell-level work: each cell's F, its block of the
// system (and inertia and gravity), and the two parallel passes that add
// them, the Jacobian's without locks by ranges of vertices and the
// residual's by cells in a fixed order. The system's layout, its
// finishing and its solve are in nodal_dilatation_system.cc.
#include <deal.II/base/exceptions.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parallel.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/solid/linear_simplex_kernel.h>
#include <tissuefem/solid/nodal_dilatation_system.h>

#include <algorithm>
#include <cstdint>

namespace tissuefem::solid
{
  template <int dim>
  void
  NodalDilatationSystem<dim>::build_parts()
  {
    // Vertex ranges of about equal size among the direct cells' vertices,
    // one per thread; a row's vertex is its dof / dim (displacement) or
    // its index - n_u (s), - n_u - n_vertices (p).
    const auto        &cells = nodal.cells;
    const unsigned int n_e   = cells.empty() ? 0 : cells[0].dofs.size();
    const unsigned int n_a   = n_e + 2 * (dim + 1);
    const auto vertex_of     = [&](const unsigned int g, const unsigned int i) {
      return i < n_e ? cells[g].dofs[i] / dim
                         : s_index[g][(i - n_e) % (dim + 1)] - n_u;
    };
    std::vector<types::global_dof_index> vertices;
    others.clear();
    for (unsigned int o = 0; o < owned_cells.size(); ++o)
      if (direct.row[std::size_t(o) * n_a] >= 0)
        for (unsigned int i = 0; i < n_a; ++i)
          vertices.push_back(vertex_of(owned_cells[o], i));
      else
        others.push_back(o);
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()),
                   vertices.end());
    const unsigned int n_parts
      = std::max(1U,
                 std::min<unsigned int>(MultithreadInfo::n_threads(),
                                        vertices.size()));
    std::vector<types::global_dof_index> first(n_parts);
    for (unsigned int t = 0; t < n_parts; ++t)
      first[t] = vertices.empty() ? 0 : vertices[t * vertices.size() / n_parts];
    parts.assign(n_parts, {});
    for (unsigned int o = 0; o < owned_cells.size(); ++o)
      {
        if (direct.row[std::size_t(o) * n_a] < 0)
          continue;
        std::vector<std::uint32_t> mask(n_parts, 0);
        for (unsigned int i = 0; i < n_a; ++i)
          {
            const auto part = std::upper_bound(first.begin(),
                                               first.end(),
                                               vertex_of(owned_cells[o], i))
                              - first.begin() - 1;
            mask[part] |= std::uint32_t(1) << i;
          }
        for (unsigned int t = 0; t < n_parts; ++t)
          if (mask[t] != 0)
            parts[t].emplace_back(o, mask[t]);
      }
  }


  template <int dim>
  void
  NodalDilatationSystem<dim>::add_blocks(
    const std::vector<const MeanDilatationPoint<dim> *> &psi,
    const std::vector<double>                           &J,
    const std::vector<Tensor<2, dim>>                   &cofactor,
    const materials::MaterialSet<dim>                   &materials,
    const Loads                                         *loads,
    const bool                                           inhomogeneous)
  {
    const auto &cells = nodal.cells;
    if (parts.empty())
      build_parts();
    const auto block
      = [&](const unsigned int o, FullMatrix<double> &K, Vector<double> &r) {
          const unsigned int g = owned_cells[o];
          add_cell(g, psi[g], J[g], cofactor[g], true, K, r);
          if (loads)
            add_loads(g, *loads, materials.density(cells[g].material_id), K, r);
        };
    // Each task computes the direct cells touching its vertices and adds
    // the rows of those vertices in place: no two tasks write one row, a
    // cell across ranges is computed by each (a few percent more), and
    // every row sums its cells in owned_cells' order, whatever the number
    // of threads.
    double *rhs_values = rhs.trilinos_vector()[0];
    parallel::apply_to_subranges(
      0U,
      static_cast<unsigned int>(parts.size()),
      [&](const unsigned int begin, const unsigned int end) {
        FullMatrix<double> K;
        Vector<double>     r;
        for (unsigned int t = begin; t < end; ++t)
          for (const auto &[o, mask] : parts[t])
            {
              block(o, K, r);
              const unsigned int n_a = r.size();
              const int         *row = &direct.row[std::size_t(o) * n_a];
              for (unsigned int i = 0; i < n_a; ++i)
                if (mask & (std::uint32_t(1) << i))
                  {
                    rhs_values[row[i]] += r(i);
                    double              *values = direct.row_values[row[i]];
                    const std::uint16_t *entry
                      = &direct.entry[(std::size_t(o) * n_a + i) * n_a];
                    for (unsigned int j = 0; j < n_a; ++j)
                      values[entry[j]] += K(i, j);
                  }
            }
      },
      1);
    // Cells with constrained or other processes' rows: through the
    // constraints, in order.
    FullMatrix<double>                   K;
    Vector<double>                       r;
    std::vector<types::global_dof_index> indices;
    for (const unsigned int o : others)
      {
        block(o, K, r);
        local_indices(owned_cells[o], indices);
        augmented_rows.distribute_local_to_global(
          K, r, indices, matrix, rhs, inhomogeneous);
      }
  }


  template <int dim>
  void
  NodalDilatationSystem<dim>::deformation(const VectorType            &u,
                                          std::vector<Tensor<2, dim>> &F,
                                          std::vector<double>         &J,
                                          std::vector<Tensor<2, dim>> &cofactor)
  {
    const auto        &cells  = nodal.cells;
    const unsigned int n_e    = cells.empty() ? 0 : cells[0].dofs.size();
    const auto        &vector = u.trilinos_vector();
    if (ghost_length != vector.MyLength())
      {
        ghost_length = vector.MyLength();
        ghost_index.resize(cells.size() * n_e);
        for (unsigned int g = 0; g < cells.size(); ++g)
          for (unsigned int i = 0; i < n_e; ++i)
            {
              ghost_index[g * n_e + i] = vector.Map().LID(
                static_cast<TrilinosWrappers::types::int_type>(
                  cells[g].dofs[i]));
              AssertThrow(ghost_index[g * n_e + i] >= 0, ExcInternalError());
            }
      }
    const double *values = vector[0];
    parallel::apply_to_subranges(
      0U,
      static_cast<unsigned int>(cells.size()),
      [&](const unsigned int begin, const unsigned int end) {
        for (unsigned int g = begin; g < end; ++g)
          {
            const auto &cell = cells[g];
            F[g]             = unit_symmetric_tensor<dim>();
            for (unsigned int i = 0; i < n_e; ++i)
              {
                const auto [node, component] = cell.node_component[i];
                F[g][component]
                  += values[ghost_index[g * n_e + i]] * cell.gradient[node];
              }
            J[g] = determinant(F[g]);
            if (J[g] != 0)
              cofactor[g] = J[g] * transpose(invert(F[g]));
          }
      },
      256);
  }


  template <int dim>
  void
  NodalDilatationSystem<dim>::add_residual(
    const std::vector<const MeanDilatationPoint<dim> *> &psi,
    const std::vector<double>                           &J,
    const std::vector<Tensor<2, dim>>                   &cofactor,
    const AffineConstraints<double>                     &rows,
    VectorType                                          &residual)
  {
    const unsigned int n_o = owned_cells.size();
    const unsigned int n_e
      = nodal.cells.empty() ? 0 : nodal.cells[0].dofs.size();
    const unsigned int n_a = n_e + 2 * (dim + 1);
    cell_residuals.resize(std::size_t(n_o) * n_e);
    parallel::apply_to_subranges(
      0U,
      n_o,
      [&](const unsigned int begin, const unsigned int end) {
        FullMatrix<double> K;
        Vector<double>     r;
        for (unsigned int o = begin; o < end; ++o)
          {
            const unsigned int g = owned_cells[o];
            add_cell(g, psi[g], J[g], cofactor[g], false, K, r);
            std::copy(r.begin(), r.begin() + n_e, &cell_residuals[o * n_e]);
          }
      },
      64);
    // In place where a cell's rows are owned and free, else through the
    // constraints; cells in a fixed order, so the sum does not depend on
    // the threads.
    double                              *values = residual.trilinos_vector()[0];
    Vector<double>                       r_u(n_e);
    std::vector<types::global_dof_index> u_indices(n_e);
    for (unsigned int o = 0; o < n_o; ++o)
      {
        const double *r   = &cell_residuals[std::size_t(o) * n_e];
        const int    *row = &direct.row[std::size_t(o) * n_a];
        if (row[0] >= 0)
          for (unsigned int i = 0; i < n_e; ++i)
            values[row[i]] += r[i];
        else
          {
            std::copy(r, r + n_e, r_u.begin());
            const auto &dofs = nodal.cells[owned_cells[o]].dofs;
            std::copy(dofs.begin(), dofs.end(), u_indices.begin());
            rows.distribute_local_to_global(r_u, u_indices, residual);
          }
      }
  }


  template <int dim>
  void
  NodalDilatationSystem<dim>::add_cell(const unsigned int              g,
                                       const MeanDilatationPoint<dim> *psi,
                                       const double                    J,
                                       const Tensor<2, dim>           &cofactor,
                                       const bool                      jacobian,
                                       FullMatrix<double>             &K,
                                       Vector<double>                 &r) const
  {
    const auto        &cell = nodal.cells[g];
    const unsigned int n_e  = cell.dofs.size();
    const unsigned int s0 = n_e, p0 = n_e + dim + 1;
    r.reinit(n_e + 2 * (dim + 1));
    // a_k = J F^{-T} grad N_k: dJ/du for (node k, component c) is a_k[c].
    std::array<Tensor<1, dim>, dim + 1> a;
    for (unsigned int k = 0; k <= dim; ++k)
      a[k] = cofactor * cell.gradient[k];
    const double *pressure_values = pressure.trilinos_vector()[0];
    double        omega           = 0; // sum_b V_g / V_b pi_b
    for (unsigned int k = 0; k <= dim; ++k)
      omega += share[g][k] * pressure_values[pressure_entry[g][k]];
    for (unsigned int i = 0; i < n_e; ++i)
      {
        const auto [k, c] = cell.node_component[i];
        r(i) += omega * a[k][c];
        if (psi)
          r(i) += psi->phi_F[c] * cell.gradient[k];
      }
    if (!jacobian)
      return;
    K.reinit(n_e + 2 * (dim + 1), n_e + 2 * (dim + 1));
    for (unsigned int i = 0; i < n_e; ++i)
      {
        const auto [k, c] = cell.node_component[i];
        if (J != 0)
          for (unsigned int j = 0; j < n_e; ++j)
            {
              // pi times the second derivative of J (nodal_dilatation.cc).
              const auto [l, d] = cell.node_component[j];
              K(i, j) += omega / J * (a[k][c] * a[l][d] - a[l][c] * a[k][d]);
            }
        // Z, and -I: the rows of p say s_b = Z_b du.
        for (unsigned int b = 0; b <= dim; ++b)
          {
            K(p0 + b, i) += share[g][b] * a[k][c];
            K(i, p0 + b) += share[g][b] * a[k][c];
          }
      }
    for (unsigned int b = 0; b <= dim; ++b)
      {
        K(s0 + b, p0 + b) -= share[g][b];
        K(p0 + b, s0 + b) -= share[g][b];
      }
    if (!psi)
      return;
    // The cell's own energy: phi_FF, and through Jbar = sum_b J_b / (d + 1)
    // its couplings Y to s and H among the s. With dF/du_(k,c) = e_c (x)
    // g_k: K_(kc)(ld) = sum_mn phi_FF[d][m][c][n] g_l[m] g_k[n], one
    // contraction with g_l per node instead of one full double contraction
    // per dof (as LinearSimplexKernel::cell_objects()).
    std::array<std::array<unsigned int, dim>, dim + 1> index;
    for (unsigned int i = 0; i < n_e; ++i)
      index[cell.node_component[i].first][cell.node_component[i].second] = i;
    const auto &grad = cell.gradient;
    for (unsigned int l = 0; l <= dim; ++l)
      {
        Tensor<3, dim> B; // B[d][c][n] = sum_m phi_FF[d][m][c][n] g_l[m]
        for (unsigned int d = 0; d < dim; ++d)
          for (unsigned int m = 0; m < dim; ++m)
            B[d] += grad[l][m] * psi->phi_FF[d][m];
        for (unsigned int k = 0; k <= dim; ++k)
          for (unsigned int c = 0; c < dim; ++c)
            for (unsigned int d = 0; d < dim; ++d)
              K(index[k][c], index[l][d]) += B[d][c] * grad[k];
      }
    for (unsigned int i = 0; i < n_e; ++i)
      {
        const auto [k, c] = cell.node_component[i];
        const double y    = psi->phi_F_theta[c] * grad[k] / (dim + 1);
        for (unsigned int b = 0; b <= dim; ++b)
          {
            K(s0 + b, i) += y;
            K(i, s0 + b) += y;
          }
      }
    const double h = psi->phi_theta_theta / ((dim + 1) * (dim + 1));
    for (unsigned int b = 0; b <= dim; ++b)
      for (unsigned int c = 0; c <= dim; ++c)
        K(s0 + b, s0 + c) += h;
  }


  template <int dim>
  void
  NodalDilatationSystem<dim>::add_loads(const unsigned int  g,
                                        const Loads        &loads,
                                        const double        rho,
                                        FullMatrix<double> &K,
                                        Vector<double>     &r) const
  {
    // The P1 simplex's mass (consistent or lumped) and gravity load, as
    // LinearSimplexKernel::cell_objects() adds them.
    using Kernel                            = LinearSimplexKernel<dim>;
    const auto                        &cell = nodal.cells[g];
    const unsigned int                 n_e  = cell.dofs.size();
    std::array<double, dim *(dim + 1)> w{};
    if (loads.inertia)
      {
        // Ghosted like u (deformation() made ghost_index from it).
        const auto &vector = loads.inertia->trilinos_vector();
        AssertDimension(vector.MyLength(), ghost_length);
        for (unsigned int j = 0; j < n_e; ++j)
          w[j] = vector[0][ghost_index[g * n_e + j]];
      }
    for (unsigned int i = 0; i < n_e; ++i)
      {
        const auto [k, c] = cell.node_component[i];
        r(i) -= Kernel::gravity_load(rho, cell.volume, loads.gravity[c]);
        for (unsigned int j = 0; j < n_e; ++j)
          {
            const auto [l, d] = cell.node_component[j];
            if (d != c)
              continue;
            const double m
              = Kernel::mass(rho, cell.volume, k == l, loads.lumped_mass);
            r(i) += m * w[j];
            K(i, j) += loads.mass_coefficient * m;
          }
      }
  }


#define TISSUEFEM_INSTANTIATE(dim)                                          \
  template void NodalDilatationSystem<dim>::build_parts();                  \
  template void NodalDilatationSystem<dim>::add_blocks(                     \
    const std::vector<const MeanDilatationPoint<dim> *> &,                  \
    const std::vector<double> &,                                            \
    const std::vector<Tensor<2, dim>> &,                                    \
    const materials::MaterialSet<dim> &,                                    \
    const Loads *,                                                          \
    const bool);                                                            \
  template void NodalDilatationSystem<dim>::deformation(                    \
    const VectorType &,                                                     \
    std::vector<Tensor<2, dim>> &,                                          \
    std::vector<double> &,                                                  \
    std::vector<Tensor<2, dim>> &);                                         \
  template void NodalDilatationSystem<dim>::add_residual(                   \
    const std::vector<const MeanDilatationPoint<dim> *> &,                  \
    const std::vector<double> &,                                            \
    const std::vector<Tensor<2, dim>> &,                                    \
    const AffineConstraints<double> &,                                      \
    VectorType &);                                                          \
  template void NodalDilatationSystem<dim>::add_cell(                       \
    const unsigned int,                                                     \
    const MeanDilatationPoint<dim> *,                                       \
    const double,                                                           \
    const Tensor<2, dim> &,                                                 \
    const bool,                                                             \
    FullMatrix<double> &,                                                   \
    Vector<double> &) const;                                                \
  template void NodalDilatationSystem<dim>::add_loads(const unsigned int,   \
                                                      const Loads &,        \
                                                      const double,         \
                                                      FullMatrix<double> &, \
                                                      Vector<double> &) const;
  TISSUEFEM_INSTANTIATE(1)
  TISSUEFEM_INSTANTIATE(2)
  TISSUEFEM_INSTANTIATE(3)
#undef TISSUEFEM_INSTANTIATE
} // namespace tissuefem::solid
