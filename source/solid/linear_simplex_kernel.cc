#include <deal.II/base/memory_consumption.h>
#include <deal.II/base/parallel.h>

#include <tissuefem/materials/tangent_projection.h>
#include <tissuefem/solid/linear_simplex_kernel.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <mutex>

namespace tissuefem::solid
{
  namespace
  {
    /// Cells per batch: enough to amortize the model's virtual call, few
    /// enough that the batch's tangents stay in the L1/L2 cache.
    constexpr unsigned int batch_size = 16;

    /// Each thread's work space for one batch: deformation gradients,
    /// fibres, stresses and tangents at its points (or, from models with
    /// their own simplex stiffness, its node blocks per unit volume), sized
    /// once.
    template <int dim>
    struct WorkSpace
    {
      std::vector<Tensor<2, dim>> F, P;
      std::vector<Tensor<1, dim>> a;
      std::vector<Tensor<4, dim>> A;
      std::vector<double>         K;
      /// The shape gradients of each point's cell.
      std::vector<const Tensor<1, dim> *> g;
    };

    template <int dim>
    WorkSpace<dim> &
    work_space()
    {
      thread_local WorkSpace<dim> space;
      return space;
    }
  } // namespace


  template <int dim>
  bool
  LinearSimplexKernel<dim>::applies(const Discretization<dim> &discretization,
                                    const CellCache<dim>      &cache)
  {
    if (dim < 2 || !discretization.simplex || discretization.fe->degree != 1
        || cache.n_scalar != n_nodes || cache.n_compon != dim)
      return false;
    // The closed-form mass equals the general path's only where its
    // quadrature integrates phi_k phi_l exactly: compare on the reference
    // values (the same on every cell), per unit volume.
    double weight = 0;
    for (unsigned int q = 0; q < cache.n_q; ++q)
      weight += discretization.cell_quadrature.weight(q);
    for (unsigned int k = 0; k < n_nodes; ++k)
      for (unsigned int l = 0; l < n_nodes; ++l)
        {
          double integral = 0;
          for (unsigned int q = 0; q < cache.n_q; ++q)
            integral += discretization.cell_quadrature.weight(q)
                        * cache.values[q * n_nodes + k]
                        * cache.values[q * n_nodes + l];
          const double exact = (k == l ? 2. : 1.) / ((dim + 1) * (dim + 2));
          if (std::abs(integral / weight - exact) > 1e-12)
            return false;
        }
    return true;
  }


  template <int dim>
  void
  LinearSimplexKernel<dim>::build(const CellCache<dim>              &cache,
                                  const FibreField<dim>             &fibres,
                                  const materials::MaterialSet<dim> &materials,
                                  const std::vector<int>  &ghost_index,
                                  const std::vector<bool> &direct,
                                  const std::vector<int>  &row,
                                  const unsigned int       n_owned_rows)
  {
    method                     = materials.tangent_method();
    project                    = materials.project_tangent();
    const unsigned int n_cells = cache.cells().size();
    gradients.resize(n_cells * n_nodes);
    volume.resize(n_cells);
    ghost.resize(n_cells * n_dofs);
    local_index.assign(cache.local_index.begin(), cache.local_index.end());
    point_begin.assign(1, 0);
    point_fibre.clear();
    point_weight.clear();
    most_points = 1;
    for (unsigned int c = 0; c < n_cells; ++c)
      {
        const unsigned int cell_index = cache.cells()[c]->active_cell_index();
        const double      *JxW        = cache.JxW(c);
        volume[c]                     = 0;
        for (unsigned int q = 0; q < cache.n_q; ++q)
          volume[c] += JxW[q];
        for (unsigned int k = 0; k < n_nodes; ++k)
          gradients[c * n_nodes + k] = cache.gradient(c, 0, k);
        for (unsigned int i = 0; i < n_dofs; ++i)
          ghost[c * n_dofs + i] = ghost_index[c * n_dofs + local_index[i]];
        const auto &material
          = materials.material(cache.cells()[c]->material_id());
        // One point per cell unless the fibre direction varies over it.
        bool uniform = true;
        if (material.uses_fibres())
          for (unsigned int q = 1; q < cache.n_q; ++q)
            uniform
              = uniform
                && (fibres.at(cell_index, q) - fibres.at(cell_index, 0)).norm()
                     == 0;
        if (uniform)
          {
            point_fibre.push_back(fibres.at(cell_index, 0));
            point_weight.push_back(volume[c]);
          }
        else
          for (unsigned int q = 0; q < cache.n_q; ++q)
            {
              point_fibre.push_back(fibres.at(cell_index, q));
              point_weight.push_back(JxW[q]);
            }
        point_begin.push_back(point_fibre.size());
        most_points
          = std::max(most_points, point_begin[c + 1] - point_begin[c]);
      }

    // Batches of at most batch_size cells of one material, in cache order
    // within a material.
    order.resize(n_cells);
    for (unsigned int c = 0; c < n_cells; ++c)
      order[c] = c;
    auto id
      = [&](const unsigned int c) { return cache.cells()[c]->material_id(); };
    std::stable_sort(order.begin(),
                     order.end(),
                     [&](const unsigned int a, const unsigned int b) {
                       return id(a) < id(b);
                     });
    batches.clear();
    for (unsigned int b = 0; b < n_cells;)
      {
        unsigned int e = b + 1;
        while (e < n_cells && e - b < batch_size
               && id(order[e]) == id(order[b]))
          ++e;
        batches.push_back({b,
                           e,
                           &materials.material(id(order[b])),
                           materials.density(id(order[b]))});
        b = e;
      }

    // Owned rows: which direct cells' entries land there, in cache order.
    row_begin.assign(n_owned_rows + 1, 0);
    // Positions are in the kernel's order (node k, component a at k * dim
    // + a); row[] is in the element's.
    for (unsigned int c = 0; c < n_cells; ++c)
      if (direct[c])
        for (unsigned int i = 0; i < n_dofs; ++i)
          ++row_begin[row[c * n_dofs + local_index[i]] + 1];
    for (unsigned int r = 0; r < n_owned_rows; ++r)
      row_begin[r + 1] += row_begin[r];
    row_positions.resize(row_begin.back());
    std::vector<unsigned int> fill(row_begin.begin(), row_begin.end() - 1);
    for (unsigned int c = 0; c < n_cells; ++c)
      if (direct[c])
        for (unsigned int i = 0; i < n_dofs; ++i)
          row_positions[fill[row[c * n_dofs + local_index[i]]]++]
            = c * n_dofs + i;
    // Direct cells' matrices go into the rows (scatter()); the others' are
    // kept.
    slot.assign(n_cells, -1);
    n_kept = 0;
    for (unsigned int c = 0; c < n_cells; ++c)
      if (!direct[c])
        slot[c] = n_kept++;
    make_phases();
    vectors.assign(n_cells * n_dofs, 0.);
    matrices.clear();
  }


  template <int dim>
  void
  LinearSimplexKernel<dim>::make_phases()
  {
    // Greedy colouring in batch order: each batch takes the lowest colour
    // no earlier batch sharing one of its nodes (ghosted index of the
    // node's first component) has.
    int n_ghost = 0;
    for (const int g : ghost)
      n_ghost = std::max(n_ghost, g + 1);
    std::vector<std::vector<unsigned int>> node_colours(n_ghost);
    std::vector<unsigned int>              colour(batches.size());
    std::vector<bool>                      taken;
    unsigned int                           n_colours = 0;
    const auto for_nodes = [&](const Batch &batch, const auto &visit) {
      for (unsigned int o = batch.begin; o < batch.end; ++o)
        for (unsigned int k = 0; k < n_nodes; ++k)
          visit(ghost[order[o] * n_dofs + k * dim]);
    };
    for (unsigned int b = 0; b < batches.size(); ++b)
      {
        taken.assign(n_colours + 1, false);
        for_nodes(batches[b], [&](const int node) {
          for (const unsigned int used : node_colours[node])
            taken[used] = true;
        });
        colour[b]
          = std::find(taken.begin(), taken.end(), false) - taken.begin();
        n_colours = std::max(n_colours, colour[b] + 1);
        for_nodes(batches[b], [&](const int node) {
          auto &list = node_colours[node];
          if (std::find(list.begin(), list.end(), colour[b]) == list.end())
            list.push_back(colour[b]);
        });
      }
    phase_begin.assign(n_colours + 1, 0);
    for (const unsigned int c : colour)
      ++phase_begin[c + 1];
    for (unsigned int p = 0; p < n_colours; ++p)
      phase_begin[p + 1] += phase_begin[p];
    phase_batches.resize(batches.size());
    std::vector<unsigned int> fill(phase_begin.begin(), phase_begin.end() - 1);
    for (unsigned int b = 0; b < batches.size(); ++b)
      phase_batches[fill[colour[b]]++] = b;
  }


  template <int dim>
  void
  LinearSimplexKernel<dim>::evaluate_batch(
    const Batch                                  &batch,
    const std::vector<unsigned int>              &order,
    const Input                                  &input,
    std::vector<std::pair<unsigned int, double>> &inverted)
  {
    // A batch has at most batch_size cells of at most most_points each.
    auto              &w          = work_space<dim>();
    const unsigned int max_points = batch_size * most_points;
    if (w.F.size() < max_points)
      {
        w.F.resize(max_points);
        w.P.resize(max_points);
        w.a.resize(max_points);
        w.A.resize(max_points);
        w.K.resize(max_points * n_packed);
        w.g.resize(max_points);
      }
    std::array<unsigned int, batch_size> first_point;
    std::array<bool, batch_size>         skipped;
    const materials::Interface<dim>     &material = *batch.material;
    const bool elastic = input.internal && input.u != nullptr;
    // Tangents where some cell of the batch wants its matrix.
    bool tangents = false;
    for (unsigned int b = batch.begin; b < batch.end && !tangents; ++b)
      tangents = wants_matrix(input, order[b]);
    // The model's own node blocks where it has them (the corotational
    // model's: half the operations of A and its contraction); a projected
    // tangent or another method needs A.
    const bool blocks = elastic && tangents && material.has_simplex_stiffness()
                        && !project
                        && (method == materials::TangentMethod::hand_coded
                            || (method == materials::TangentMethod::fastest
                                && material.has_hand_coded_tangent()));

    // Deformation gradients of the batch's cells, one per point.
    unsigned int n_points = 0;
    for (unsigned int b = batch.begin; b < batch.end; ++b)
      {
        const unsigned int c         = order[b];
        first_point[b - batch.begin] = n_points;
        skipped[b - batch.begin]     = true;
        if (input.cells && !(*input.cells)[c])
          continue;
        const Tensor<2, dim> Fc = elastic ? deformation_gradient(c, input.u)
                                          : unit_symmetric_tensor<dim>();
        if (elastic && !material.admits_inversion())
          {
            const double det = determinant(Fc);
            if (det <= 0)
              {
                inverted.emplace_back(c, det);
                continue;
              }
          }
        skipped[b - batch.begin] = false;
        for (unsigned int p = point_begin[c]; p < point_begin[c + 1]; ++p)
          {
            w.F[n_points] = Fc;
            w.a[n_points] = point_fibre[p];
            w.g[n_points] = &gradients[c * n_nodes];
            ++n_points;
          }
      }
    if (elastic && n_points > 0)
      {
        if (blocks)
          for (unsigned int p = 0; p < n_points; ++p)
            material.simplex_stiffness(
              w.F[p], w.a[p], w.g[p], w.P[p], &w.K[p * n_packed]);
        else if (tangents)
          {
            material.stresses_and_tangents(
              n_points, w.F.data(), w.a.data(), w.P.data(), w.A.data(), method);
            if (project)
              for (unsigned int p = 0; p < n_points; ++p)
                materials::project_to_positive_definite(w.A[p]);
          }
        else
          material.stresses(n_points, w.F.data(), w.a.data(), w.P.data());
      }

    for (unsigned int b = batch.begin; b < batch.end; ++b)
      cell_objects(order[b],
                   skipped[b - batch.begin],
                   first_point[b - batch.begin],
                   batch.density,
                   input,
                   blocks);
  }


  template <int dim>
  void
  LinearSimplexKernel<dim>::cell_objects(const unsigned int c,
                                         const bool         skipped,
                                         const unsigned int first_point,
                                         const double       rho,
                                         const Input       &input,
                                         const bool         blocks)
  {
    const auto &w       = work_space<dim>();
    const bool  elastic = input.internal && input.u != nullptr;
    double     *r       = &vectors[c * n_dofs];
    // A kept matrix, or a direct cell's on its way into the matrix.
    std::array<double, n_packed> direct_K;
    double                      *K = !wants_matrix(input, c) ? nullptr
                                     : slot[c] >= 0 ? &matrices[slot[c] * n_packed]
                                     : input.matrix_rows ? direct_K.data()
                                                         : nullptr;
    std::fill(r, r + n_dofs, 0.);
    if (K)
      std::fill(K, K + n_packed, 0.);
    // Cells not asked for, and inverted ones (the caller throws).
    if (skipped)
      return;
    const Tensor<1, dim> *g = &gradients[c * n_nodes];
    if (elastic)
      {
        // f_k = sum_points weight P g_k; K_(ka)(lb) = sum weight A_ambn
        // g_km g_ln.
        unsigned int p = first_point;
        for (unsigned int s = point_begin[c]; s < point_begin[c + 1]; ++s, ++p)
          {
            const double weight = point_weight[s];
            for (unsigned int k = 0; k < n_nodes; ++k)
              {
                const Tensor<1, dim> f = weight * (w.P[p] * g[k]);
                for (unsigned int i = 0; i < dim; ++i)
                  r[k * dim + i] += f[i];
              }
            if (!K)
              continue;
            if (blocks)
              {
                const double *Kp = &w.K[p * n_packed];
                for (unsigned int e = 0; e < n_packed; ++e)
                  K[e] += weight * Kp[e];
                continue;
              }
            for (unsigned int k = 0; k < n_nodes; ++k)
              {
                // B[a][b][n] = weight A[a][m][b][n] g_k[m]
                Tensor<3, dim> B;
                for (unsigned int i = 0; i < dim; ++i)
                  for (unsigned int m = 0; m < dim; ++m)
                    B[i] += (weight * g[k][m]) * w.A[p][i][m];
                for (unsigned int l = k; l < n_nodes; ++l)
                  {
                    double *Kkl = K + block(k, l);
                    for (unsigned int i = 0; i < dim; ++i)
                      for (unsigned int j = 0; j < dim; ++j)
                        Kkl[i * dim + j] += B[i][j] * g[l];
                  }
              }
          }
      }
    const double V = volume[c];
    if (input.external)
      for (unsigned int k = 0; k < n_nodes; ++k)
        for (unsigned int i = 0; i < dim; ++i)
          r[k * dim + i] -= gravity_load(rho, V, input.gravity[i]);
    if (input.w)
      {
        const int *G      = &ghost[c * n_dofs];
        const bool lumped = input.lumped_mass;
        for (unsigned int k = 0; k < n_nodes; ++k)
          for (unsigned int l = lumped ? k : 0; l < (lumped ? k + 1 : n_nodes);
               ++l)
            for (unsigned int i = 0; i < dim; ++i)
              r[k * dim + i]
                += mass(rho, V, k == l, lumped) * input.w[G[l * dim + i]];
      }
    if (K)
      {
        const double shift = input.mass_jacobian_coefficient;
        // Only the node blocks k <= l are kept (K is symmetric: A_ambn =
        // A_bnam).
        for (unsigned int k = 0; k < n_nodes; ++k)
          for (unsigned int l = k; l < n_nodes; ++l)
            for (unsigned int i = 0; i < dim; ++i)
              K[block(k, l) + i * dim + i]
                += shift * mass(rho, V, k == l, input.lumped_mass);
        if (slot[c] < 0)
          scatter(c, K, input);
      }
  }


  template <int dim>
  void
  LinearSimplexKernel<dim>::scatter(const unsigned int c,
                                    const double      *K,
                                    const Input       &input) const
  {
    const std::uint16_t *entries = input.matrix_entries->data();
    const int           *rows    = &(*input.matrix_row_of)[c * n_dofs];
    for (unsigned int i = 0; i < n_dofs; ++i)
      {
        const unsigned int k = i / dim, a = i % dim;
        double            *values = (*input.matrix_rows)[rows[local_index[i]]];
        const std::uint16_t *e
          = &entries[(c * n_dofs + local_index[i]) * n_dofs];
        // Row (k, a): of block (k, l) its row a, of block (l, k) (l < k,
        // the one kept) its column a.
        for (unsigned int l = 0; l < n_nodes; ++l)
          {
            const unsigned int start
              = l >= k ? block(k, l) + a * dim : block(l, k) + a;
            const unsigned int  stride = l >= k ? 1 : dim;
            const unsigned int *J      = &local_index[l * dim];
            if (mass_only)
              values[e[J[a]]] += K[start + a * stride];
            else
              for (unsigned int b = 0; b < dim; ++b)
                values[e[J[b]]] += K[start + b * stride];
          }
      }
  }


  template <int dim>
  std::vector<std::pair<unsigned int, double>>
  LinearSimplexKernel<dim>::evaluate(const Input &input)
  {
    // A direct cell left out of jacobian_cells would add nothing to the
    // matrix: a Jacobian into the rows is of all cells.
    Assert(!input.jacobian || !input.matrix_rows
             || (input.matrix_row_of && input.matrix_entries
                 && !input.jacobian_cells),
           ExcInternalError());
    if (input.jacobian)
      matrices.resize(n_kept * n_packed);
    mass_only = !(input.internal && input.u != nullptr);
    // An active region computes its own cells only, batched afresh, so
    // that its cost follows its size.
    const bool compact = input.cells && !input.jacobian;
    if (compact)
      select(*input.cells);
    const auto &cells = compact ? selection : order;
    const auto &run   = compact ? selection_batches : batches;
    std::vector<std::pair<unsigned int, double>> inverted;
    std::mutex                                   lock;
    // Matrices into the Trilinos rows: a phase at a time (no two batches of
    // one share a node). Otherwise all batches at once.
    const bool into_matrix = input.jacobian && input.matrix_rows;
    Assert(!into_matrix || !compact, ExcInternalError());
    const unsigned int n_phases = into_matrix ? phase_begin.size() - 1 : 1;
    for (unsigned int p = 0; p < n_phases; ++p)
      parallel::apply_to_subranges(
        into_matrix ? phase_begin[p] : 0u,
        into_matrix ? phase_begin[p + 1]
                    : static_cast<unsigned int>(run.size()),
        [&](const unsigned int begin, const unsigned int end) {
          std::vector<std::pair<unsigned int, double>> found;
          for (unsigned int b = begin; b < end; ++b)
            evaluate_batch(run[into_matrix ? phase_batches[b] : b],
                           cells,
                           input,
                           found);
          if (!found.empty())
            {
              std::lock_guard<std::mutex> guard(lock);
              inverted.insert(inverted.end(), found.begin(), found.end());
            }
        },
        8);
    std::sort(inverted.begin(), inverted.end());
    return inverted;
  }


  template <int dim>
  void
  LinearSimplexKernel<dim>::select(const std::vector<bool> &cells)
  {
    selection.clear();
    selection_batches.clear();
    for (const Batch &batch : batches)
      for (unsigned int b = batch.begin; b < batch.end; ++b)
        if (cells[order[b]])
          {
            const auto size = static_cast<unsigned int>(selection.size());
            if (selection_batches.empty()
                || selection_batches.back().material != batch.material
                || selection_batches.back().end
                     == selection_batches.back().begin + batch_size)
              selection_batches.push_back(
                {size, size, batch.material, batch.density});
            selection.push_back(order[b]);
            ++selection_batches.back().end;
          }
  }


  template <int dim>
  Tensor<2, dim>
  LinearSimplexKernel<dim>::deformation_gradient(const unsigned int c,
                                                 const double      *u) const
  {
    Tensor<2, dim> F = unit_symmetric_tensor<dim>();
    for (unsigned int k = 0; k < n_nodes; ++k)
      {
        const Tensor<1, dim> &g = gradients[c * n_nodes + k];
        const int            *G = &ghost[c * n_dofs + k * dim];
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            F[i][j] += u[G[i]] * g[j];
      }
    return F;
  }


  template <int dim>
  double
  LinearSimplexKernel<dim>::sum_over_batches(
    const std::function<double(const Batch &)> &batch_sum) const
  {
    std::vector<double> sums(batches.size());
    parallel::apply_to_subranges(
      0u,
      static_cast<unsigned int>(batches.size()),
      [&](const unsigned int begin, const unsigned int end) {
        for (unsigned int b = begin; b < end; ++b)
          sums[b] = batch_sum(batches[b]);
      },
      8);
    double sum = 0;
    for (const double value : sums)
      sum += value;
    return sum;
  }


  template <int dim>
  double
  LinearSimplexKernel<dim>::stored_energy(const double *u) const
  {
    return sum_over_batches([&](const Batch &batch) {
      double energy = 0;
      for (unsigned int o = batch.begin; o < batch.end; ++o)
        {
          const unsigned int   c = order[o];
          const Tensor<2, dim> F = deformation_gradient(c, u);
          if (!batch.material->admits_inversion() && !(determinant(F) > 0))
            return std::numeric_limits<double>::infinity();
          for (unsigned int p = point_begin[c]; p < point_begin[c + 1]; ++p)
            energy += batch.material->energy_density(F, point_fibre[p])
                      * point_weight[p];
        }
      return energy;
    });
  }


  template <int dim>
  double
  LinearSimplexKernel<dim>::kinetic_energy(const double *v) const
  {
    return sum_over_batches([&](const Batch &batch) {
      double energy = 0;
      for (unsigned int o = batch.begin; o < batch.end; ++o)
        {
          const unsigned int c = order[o];
          Tensor<1, dim>     sum;
          double             squares = 0;
          for (unsigned int k = 0; k < n_nodes; ++k)
            for (unsigned int i = 0; i < dim; ++i)
              {
                const double value = v[ghost[c * n_dofs + k * dim + i]];
                sum[i] += value;
                squares += value * value;
              }
          energy += volume[c] * (squares + sum.norm_square());
        }
      return 0.5 * batch.density * energy / ((dim + 1) * (dim + 2));
    });
  }


  template <int dim>
  void
  LinearSimplexKernel<dim>::add_direct(double *residual) const
  {
    const unsigned int n_rows = row_begin.size() - 1;
    parallel::apply_to_subranges(
      0u,
      n_rows,
      [&](const unsigned int begin, const unsigned int end) {
        for (unsigned int r = begin; r < end; ++r)
          {
            double sum = 0;
            for (unsigned int s = row_begin[r]; s < row_begin[r + 1]; ++s)
              sum += vectors[row_positions[s]];
            residual[r] += sum;
          }
      },
      256);
  }


  template <int dim>
  std::size_t
  LinearSimplexKernel<dim>::memory_consumption() const
  {
    using MemoryConsumption::memory_consumption;
    return memory_consumption(order) + memory_consumption(selection)
           + (batches.capacity() + selection_batches.capacity()) * sizeof(Batch)
           + memory_consumption(gradients) + memory_consumption(volume)
           + memory_consumption(ghost) + memory_consumption(local_index)
           + memory_consumption(point_begin) + memory_consumption(point_fibre)
           + memory_consumption(point_weight) + memory_consumption(row_begin)
           + memory_consumption(row_positions)
           + memory_consumption(phase_batches) + memory_consumption(phase_begin)
           + memory_consumption(slot) + memory_consumption(vectors)
           + memory_consumption(matrices);
  }


  template class LinearSimplexKernel<1>;
  template class LinearSimplexKernel<2>;
  template class LinearSimplexKernel<3>;
} // namespace tissuefem::solid
