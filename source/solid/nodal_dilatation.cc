#include <deal.II/base/work_stream.h>
#include <deal.II/lac/full_matrix.h>

#include <tissuefem/materials/tangent_projection.h>
#include <tissuefem/solid/mean_dilatation.h>
#include <tissuefem/solid/nodal_dilatation.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

namespace tissuefem::solid
{
  template <int dim>
  NodalDilatation<dim>::NodalDilatation(
    const Discretization<dim> &discretization)
  {
    const auto &dof_handler = discretization.dof_handler;
    const auto &fe          = *discretization.fe;
    const auto &mesh        = dof_handler.get_triangulation();
    n_active_cells          = mesh.n_active_cells();
    n_vertices              = mesh.n_vertices();

    std::vector<bool> needed(mesh.n_vertices(), false);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          needed[cell->vertex_index(v)] = true;

    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (cell->is_artificial())
          continue;
        bool touches = false;
        for (const unsigned int v : cell->vertex_indices())
          touches = touches || needed[cell->vertex_index(v)];
        if (!touches)
          continue;
        Cell c;
        c.active_index = cell->active_cell_index();
        c.material_id  = cell->material_id();
        c.owned        = cell->is_locally_owned();
        c.centre       = cell->center();
        // Hat-function gradients of the affine simplex: rows of M^{-1},
        // M = [x_1 - x_0, ..., x_d - x_0]; the first is minus their sum.
        Tensor<2, dim> M;
        for (unsigned int k = 1; k <= dim; ++k)
          for (unsigned int i = 0; i < dim; ++i)
            M[i][k - 1] = cell->vertex(k)[i] - cell->vertex(0)[i];
        const Tensor<2, dim> M_inverse = invert(M);
        double               factorial = 1;
        for (unsigned int k = 2; k <= dim; ++k)
          factorial *= k;
        c.volume      = std::abs(determinant(M)) / factorial;
        c.gradient[0] = Tensor<1, dim>();
        for (unsigned int k = 1; k <= dim; ++k)
          {
            c.gradient[k] = M_inverse[k - 1];
            c.gradient[0] -= c.gradient[k];
          }
        for (const unsigned int v : cell->vertex_indices())
          c.vertex[v] = cell->vertex_index(v);
        c.dofs.resize(fe.n_dofs_per_cell());
        cell->get_dof_indices(c.dofs);
        for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
          {
            const auto [component, node] = fe.system_to_component_index(i);
            c.node_component.emplace_back(node, component);
          }
        for (const unsigned int v : cell->vertex_indices())
          if (needed[c.vertex[v]])
            around[c.vertex[v]].push_back(cells.size());
        cells.push_back(std::move(c));
      }
    volume_around.assign(n_vertices, 0.);
    for (const auto &[vertex, list] : around)
      for (const unsigned int g : list)
        volume_around[vertex] += cells[g].volume;

    double sum = 0;
    for (unsigned int q = 0; q < discretization.cell_quadrature.size(); ++q)
      sum += discretization.cell_quadrature.weight(q);
    for (unsigned int q = 0; q < discretization.cell_quadrature.size(); ++q)
      weights.push_back(discretization.cell_quadrature.weight(q) / sum);
  }


  template <int dim>
  const std::vector<typename NodalDilatation<dim>::Patch> &
  NodalDilatation<dim>::patch_list() const
  {
    // Built on first use: only the wide matrix needs them (the sparser
    // system of nodal_dilatation_system.h and the residual do not), and
    // on a large mesh they cost more than the rest of the set-up.
    std::lock_guard<std::mutex> lock(patch_mutex);
    if (!patches_built)
      build_patches();
    patches_built = true;
    return patches;
  }


  template <int dim>
  void
  NodalDilatation<dim>::build_patches() const
  {
    for (unsigned int e = 0; e < cells.size(); ++e)
      if (cells[e].owned)
        {
          Patch                          patch;
          std::map<unsigned int, double> weight;
          for (const unsigned int v : cells[e].vertex)
            for (const unsigned int g : around.at(v))
              weight[g] += cells[g].volume / ((dim + 1) * volume_around[v]);
          patch.cell = e;
          for (const auto &[g, c] : weight)
            {
              patch.members.push_back(g);
              patch.weights.push_back(c);
              patch.dofs.insert(patch.dofs.end(),
                                cells[g].dofs.begin(),
                                cells[g].dofs.end());
            }
          std::sort(patch.dofs.begin(), patch.dofs.end());
          patch.dofs.erase(std::unique(patch.dofs.begin(), patch.dofs.end()),
                           patch.dofs.end());
          const auto position = [&](const types::global_dof_index i) {
            return static_cast<unsigned int>(
              std::lower_bound(patch.dofs.begin(), patch.dofs.end(), i)
              - patch.dofs.begin());
          };
          for (const unsigned int g : patch.members)
            {
              std::vector<unsigned int> positions;
              for (const auto i : cells[g].dofs)
                positions.push_back(position(i));
              patch.member_positions.push_back(positions);
            }
          for (const auto i : cells[e].dofs)
            patch.own_positions.push_back(position(i));
          patches.push_back(std::move(patch));
        }
  }


  template <int dim>
  void
  NodalDilatation<dim>::add_sparsity(
    const AffineConstraints<double>   &constraints,
    TrilinosWrappers::SparsityPattern &sparsity) const
  {
    for (const Patch &patch : patch_list())
      constraints.add_entries_local_to_global(patch.dofs, sparsity, false);
  }


  template <int dim>
  Tensor<2, dim>
  NodalDilatation<dim>::deformation_gradient(const Cell       &cell,
                                             const VectorType &u) const
  {
    Tensor<2, dim> F = unit_symmetric_tensor<dim>();
    for (unsigned int i = 0; i < cell.dofs.size(); ++i)
      {
        const auto [node, component] = cell.node_component[i];
        F[component] += u[cell.dofs[i]] * cell.gradient[node];
      }
    return F;
  }


  template <int dim>
  std::vector<double>
  NodalDilatation<dim>::volume_times_J(const std::vector<double> &J) const
  {
    std::vector<double> sums(volume_around.size(), 0.);
    for (unsigned int g = 0; g < cells.size(); ++g)
      for (const unsigned int v : cells[g].vertex)
        sums[v] += cells[g].volume * J[g];
    return sums;
  }


  template <int dim>
  double
  NodalDilatation<dim>::vertex_average(const Cell                &cell,
                                       const std::vector<double> &sums) const
  {
    double theta = 0;
    for (const unsigned int v : cell.vertex)
      theta += sums[v] / volume_around[v] / (dim + 1);
    return theta;
  }


  template <int dim>
  std::vector<double>
  NodalDilatation<dim>::dilatations(const VectorType &u) const
  {
    // One pass over the cells and one over the owned ones (the same as
    // sum_g c_g J_g over the patch, in O(cells)).
    std::vector<double> J(cells.size());
    for (unsigned int g = 0; g < cells.size(); ++g)
      J[g] = determinant(deformation_gradient(cells[g], u));
    const std::vector<double> sums = volume_times_J(J);
    std::vector<double>       result(n_active_cells,
                               std::numeric_limits<double>::quiet_NaN());
    for (const Cell &cell : cells)
      if (cell.owned)
        result[cell.active_index] = vertex_average(cell, sums);
    return result;
  }


  template <int dim>
  double
  NodalDilatation<dim>::dilatation(const Patch               &patch,
                                   const std::vector<double> &J) const
  {
    double theta = 0;
    for (unsigned int m = 0; m < patch.members.size(); ++m)
      theta += patch.weights[m] * J[patch.members[m]];
    return theta;
  }


  template <int dim>
  std::vector<std::tuple<unsigned int, double, Point<dim>>>
  NodalDilatation<dim>::assemble(const VectorType                  &u,
                                 const materials::MaterialSet<dim> &materials,
                                 const FibreField<dim>             &fibres,
                                 const bool                         jacobian,
                                 const AffineConstraints<double>   &rows,
                                 const bool  inhomogeneous,
                                 MatrixType &matrix,
                                 VectorType &residual) const
  {
    std::vector<std::tuple<unsigned int, double, Point<dim>>> inverted;
    // F, J and J F^{-T} (= dJ/dF) of every cell this process needs, once.
    std::vector<Tensor<2, dim>> F(cells.size()), cofactor(cells.size());
    std::vector<double>         J(cells.size());
    for (unsigned int g = 0; g < cells.size(); ++g)
      {
        F[g] = deformation_gradient(cells[g], u);
        J[g] = determinant(F[g]);
        if (J[g] != 0)
          cofactor[g] = J[g] * transpose(invert(F[g]));
      }

    // One patch per task; the copier adds in order (WorkStream).
    struct Copy
    {
      const Patch       *patch    = nullptr;
      bool               defined  = true;
      double             smallest = 0;
      FullMatrix<double> K;
      Vector<double>     r;
    };
    struct Scratch
    {
      Vector<double> w;
    };
    auto worker = [&](const typename std::vector<Patch>::const_iterator &it,
                      Scratch                                           &s,
                      Copy                                              &copy) {
      const Patch &patch    = *it;
      copy.patch            = &patch;
      const Cell  &cell     = cells[patch.cell];
      const auto  &material = materials.material(cell.material_id);
      const double J_e      = J[patch.cell];
      const double theta    = dilatation(patch, J);
      copy.defined          = theta / J_e > 0
                     && (material.admits_inversion() || (J_e > 0 && theta > 0));
      if (!copy.defined)
        {
          copy.smallest = std::min(J_e, theta);
          return;
        }
      const MeanDilatationPoint<dim> psi
        = derivatives(cell, F[patch.cell], theta, materials, fibres, jacobian);

      // w = dtheta/du = sum_g c_g (J F^{-T})_g : dF_g/du.
      const unsigned int n = patch.dofs.size();
      s.w.reinit(n);
      for (unsigned int m = 0; m < patch.members.size(); ++m)
        {
          const Cell &g = cells[patch.members[m]];
          for (unsigned int i = 0; i < g.dofs.size(); ++i)
            {
              const auto [node, component] = g.node_component[i];
              s.w[patch.member_positions[m][i]]
                += patch.weights[m]
                   * (cofactor[patch.members[m]][component] * g.gradient[node]);
            }
        }
      // Residual: Psi_F : dF_e/du + Psi_theta w.
      copy.r.reinit(n);
      for (unsigned int i = 0; i < cell.dofs.size(); ++i)
        {
          const auto [node, component] = cell.node_component[i];
          copy.r[patch.own_positions[i]]
            += psi.phi_F[component] * cell.gradient[node];
        }
      copy.r.add(psi.phi_theta, s.w);
      if (jacobian)
        {
          copy.K.reinit(n, n);
          add_tangent(patch, cell, psi, J, cofactor, s.w, copy.K);
        }
    };
    auto copier = [&](const Copy &copy) {
      const Cell &cell = cells[copy.patch->cell];
      if (!copy.defined)
        inverted.emplace_back(cell.active_index, copy.smallest, cell.centre);
      else if (jacobian)
        rows.distribute_local_to_global(
          copy.K, copy.r, copy.patch->dofs, matrix, residual, inhomogeneous);
      else
        rows.distribute_local_to_global(copy.r, copy.patch->dofs, residual);
    };
    const std::vector<Patch> &list = patch_list();
    WorkStream::run(
      list.cbegin(), list.cend(), worker, copier, Scratch(), Copy());
    return inverted;
  }


  template <int dim>
  MeanDilatationPoint<dim>
  NodalDilatation<dim>::derivatives(
    const Cell                        &cell,
    const Tensor<2, dim>              &F,
    const double                       theta,
    const materials::MaterialSet<dim> &materials,
    const FibreField<dim>             &fibres,
    const bool                         jacobian) const
  {
    // Psi-hat(F, theta) = Psi(Fbar), Fbar = (theta / J)^(1/d) F, and its
    // derivatives, summed over the cell's points (the fibre may vary
    // between them; F does not).
    const auto          &material = materials.material(cell.material_id);
    const Tensor<2, dim> F_bar = std::pow(theta / determinant(F), 1. / dim) * F;
    // One point's derivatives, for the fibre @p a.
    const auto evaluate
      = [&](const Tensor<1, dim> &a, MeanDilatationPoint<dim> &point) {
          if (jacobian)
            {
              Tensor<2, dim> P_bar;
              Tensor<4, dim> A_bar;
              material.stress_and_tangent(
                F_bar, a, P_bar, A_bar, materials.tangent_method());
              if (materials.project_tangent())
                materials::project_to_positive_definite(A_bar);
              mean_dilatation_stress_and_tangent(F, theta, P_bar, A_bar, point);
            }
          else
            mean_dilatation_stress(F, theta, material.stress(F_bar, a), point);
        };
    MeanDilatationPoint<dim> sum;
    // Without fibres one evaluation serves every point (weights sum to 1):
    // no bookkeeping per point, and the residual's calls (every line-search
    // trial) do not sum the tangent's zeros.
    if (!material.uses_fibres())
      {
        evaluate(fibres.at(cell.active_index, 0), sum);
        sum.phi_F *= cell.volume;
        sum.phi_theta *= cell.volume;
        if (jacobian)
          {
            sum.phi_FF *= cell.volume;
            sum.phi_F_theta *= cell.volume;
            sum.phi_theta_theta *= cell.volume;
          }
        return sum;
      }
    // Points with the same fibre share one evaluation: F is constant on
    // the cell.
    std::vector<bool> done(weights.size(), false);
    for (unsigned int q = 0; q < weights.size(); ++q)
      {
        if (done[q])
          continue;
        const Tensor<1, dim> &a      = fibres.at(cell.active_index, q);
        double                weight = 0;
        for (unsigned int r = q; r < weights.size(); ++r)
          if (!done[r] && fibres.at(cell.active_index, r) == a)
            {
              weight += weights[r];
              done[r] = true;
            }
        MeanDilatationPoint<dim> point;
        evaluate(a, point);
        const double v = weight * cell.volume;
        sum.phi_F += v * point.phi_F;
        sum.phi_theta += v * point.phi_theta;
        sum.phi_FF += v * point.phi_FF;
        sum.phi_F_theta += v * point.phi_F_theta;
        sum.phi_theta_theta += v * point.phi_theta_theta;
      }
    return sum;
  }


  template <int dim>
  void
  NodalDilatation<dim>::add_tangent(const Patch                       &patch,
                                    const Cell                        &cell,
                                    const MeanDilatationPoint<dim>    &psi,
                                    const std::vector<double>         &J,
                                    const std::vector<Tensor<2, dim>> &cofactor,
                                    const Vector<double>              &w,
                                    FullMatrix<double>                &K) const
  {
    const unsigned int n = w.size(), n_e = cell.dofs.size();
    // F-F, F-theta and theta-theta blocks; dF_e/du_i = e_c (x) grad N_k.
    std::vector<Tensor<2, dim>> dF(n_e);
    for (unsigned int i = 0; i < n_e; ++i)
      {
        const auto [node, component] = cell.node_component[i];
        dF[i][component]             = cell.gradient[node];
      }
    std::vector<unsigned int> support; // where w is not zero
    for (unsigned int a = 0; a < n; ++a)
      if (w[a] != 0)
        support.push_back(a);
    for (unsigned int i = 0; i < n_e; ++i)
      {
        const unsigned int   I = patch.own_positions[i];
        const Tensor<2, dim> AdF
          = double_contract<2, 0, 3, 1>(psi.phi_FF, dF[i]);
        const double coupling = scalar_product(psi.phi_F_theta, dF[i]);
        for (unsigned int j = 0; j < n_e; ++j)
          K(I, patch.own_positions[j]) += scalar_product(AdF, dF[j]);
        for (const unsigned int b : support)
          {
            K(I, b) += coupling * w[b];
            K(b, I) += coupling * w[b];
          }
      }
    for (const unsigned int a : support)
      for (const unsigned int b : support)
        K(a, b) += psi.phi_theta_theta * w[a] * w[b];
    // Psi_theta times the second derivative of theta: sum_g c_g d2J_g,
    // d2J[d, D] = J (tr(F^-1 D) tr(F^-1 d) - tr(F^-1 D F^-1 d)), which with
    // a_k = J F^{-T} grad N_k is (a_k[c] a_l[c'] - a_l[c] a_k[c']) / J.
    for (unsigned int m = 0; m < patch.members.size(); ++m)
      {
        const unsigned int g     = patch.members[m];
        const Cell        &other = cells[g];
        const double       scale = psi.phi_theta * patch.weights[m] / J[g];
        std::array<Tensor<1, dim>, dim + 1> a;
        for (unsigned int k = 0; k <= dim; ++k)
          a[k] = cofactor[g] * other.gradient[k];
        const auto &positions = patch.member_positions[m];
        for (unsigned int i = 0; i < other.dofs.size(); ++i)
          {
            const auto [k, ci] = other.node_component[i];
            for (unsigned int j = 0; j < other.dofs.size(); ++j)
              {
                const auto [l, cj] = other.node_component[j];
                K(positions[i], positions[j])
                  += scale * (a[k][ci] * a[l][cj] - a[l][ci] * a[k][cj]);
              }
          }
      }
  }


  template class NodalDilatation<1>;
  template class NodalDilatation<2>;
  template class NodalDilatation<3>;
} // namespace tissuefem::solid
