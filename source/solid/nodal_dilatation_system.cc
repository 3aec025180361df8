#include <deal.II/base/exceptions.h>
#include <deal.II/base/parallel.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_index_access.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/solid/augmented_system.h>
#include <tissuefem/solid/matrix_rows.h>
#include <tissuefem/solid/nodal_dilatation_system.h>

#include <algorithm>

namespace tissuefem::solid
{


  template <int dim>
  bool
  NodalDilatationSystem<dim>::applies(
    const NodalDilatation<dim>      &nodal,
    const AffineConstraints<double> &constraints)
  {
    if (dim < 2)
      return false;
    bool fits = true;
    for (const auto &line : constraints.get_lines())
      fits = fits && line.entries.empty();
    // dof(node k, component c) = dim v + c for some vertex number v.
    for (const auto &cell : nodal.cells)
      for (unsigned int i = 0; i < cell.dofs.size(); ++i)
        {
          const auto [node, component] = cell.node_component[i];
          fits = fits && cell.dofs[i] % dim == component;
          for (unsigned int j = 0; j < cell.dofs.size(); ++j)
            fits = fits
                   && (cell.node_component[j].first != node
                       || cell.dofs[j] / dim == cell.dofs[i] / dim);
        }
    // Every process must choose alike: the system is built collectively.
    return Utilities::MPI::min(fits ? 1 : 0, parallel_tools::communicator())
           == 1;
  }


  template <int dim>
  NodalDilatationSystem<dim>::NodalDilatationSystem(
    const Discretization<dim>  &discretization,
    const NodalDilatation<dim> &nodal)
      : nodal(nodal)
  {
    n_u        = discretization.n_dofs();
    n_vertices = n_u / dim;
    // s, then p, at each vertex.
    owned    = with_vertex_unknowns(discretization.locally_owned, dim, 2);
    relevant = with_vertex_unknowns(discretization.locally_relevant, dim, 2);

    const auto &cells         = nodal.cells;
    const auto &volume_around = nodal.volume_around;
    for (unsigned int g = 0; g < cells.size(); ++g)
      if (cells[g].owned)
        owned_cells.push_back(g);
    s_index.resize(cells.size());
    share.resize(cells.size());
    for (unsigned int g = 0; g < cells.size(); ++g)
      {
        for (unsigned int i = 0; i < cells[g].dofs.size(); ++i)
          if (cells[g].node_component[i].second == 0)
            s_index[g][cells[g].node_component[i].first]
              = n_u + cells[g].dofs[i] / dim;
        // V_g / V_b, used at the vertices of owned cells (whose cells are
        // all here; V_b is 0 at the others).
        for (unsigned int k = 0; k <= dim; ++k)
          share[g][k] = cells[g].owned
                          ? cells[g].volume / volume_around[cells[g].vertex[k]]
                          : 0.;
      }

    // The couplings of each owned cell's displacement, s and p.
    copy_dirichlet_lines(discretization.constraints, relevant, augmented_rows);
    TrilinosWrappers::SparsityPattern    sparsity(owned,
                                               owned,
                                               relevant,
                                               parallel_tools::communicator());
    std::vector<types::global_dof_index> indices;
    for (const unsigned int g : owned_cells)
      {
        local_indices(g, indices);
        augmented_rows.add_entries_local_to_global(indices, sparsity, false);
      }
    sparsity.compress();
    matrix.reinit(sparsity);
    rhs.reinit(owned, relevant, parallel_tools::communicator(), true);
    pressure_sum.reinit(owned, relevant, parallel_tools::communicator(), true);
    pressure.reinit(owned, relevant, parallel_tools::communicator());
    build_direct_access(discretization.constraints);
  }


  template <int dim>
  void
  NodalDilatationSystem<dim>::build_direct_access(
    const AffineConstraints<double> &constraints)
  {
    // Where each owned cell's rows and entries lie in the matrix's and the
    // right-hand side's arrays, for cells whose displacement dofs are all
    // owned and free (then so are their vertices' s and p): those add in
    // place, the others through deal.II's constraints.
    const auto        &cells = nodal.cells;
    const unsigned int n_a
      = cells.empty() ? 0 : cells[0].dofs.size() + 2 * (dim + 1);
    direct.row_values = row_value_pointers(matrix);
    direct.row.assign(owned_cells.size() * n_a, -1);
    direct.entry.assign(owned_cells.size() * n_a * n_a, 0);
    const auto &ghosts = pressure.trilinos_vector().Map();
    pressure_entry.resize(cells.size());
    for (unsigned int g = 0; g < cells.size(); ++g)
      for (unsigned int k = 0; k <= dim; ++k)
        pressure_entry[g][k] = ghosts.LID(
          static_cast<TrilinosWrappers::types::int_type>(s_index[g][k]));
    std::vector<types::global_dof_index> indices;
    for (unsigned int o = 0; o < owned_cells.size(); ++o)
      {
        const auto &cell = cells[owned_cells[o]];
        bool        free = true;
        for (const auto i : cell.dofs)
          free = free && owned.is_element(i) && !constraints.is_constrained(i);
        if (!free)
          continue;
        local_indices(owned_cells[o], indices);
        for (unsigned int i = 0; i < n_a; ++i)
          {
            const int r = owned.index_within_set(indices[i]);
            direct.row[std::size_t(o) * n_a + i] = r;
            for (unsigned int j = 0; j < n_a; ++j)
              {
                const int position = entry_in_row(matrix, r, indices[j]);
                AssertThrow(position < 65536, ExcInternalError());
                direct.entry[(std::size_t(o) * n_a + i) * n_a + j] = position;
              }
          }
      }
  }


  template <int dim>
  void
  NodalDilatationSystem<dim>::local_indices(
    const unsigned int                    g,
    std::vector<types::global_dof_index> &indices) const
  {
    indices = nodal.cells[g].dofs;
    for (unsigned int k = 0; k <= dim; ++k)
      indices.push_back(s_index[g][k]);
    for (unsigned int k = 0; k <= dim; ++k)
      indices.push_back(s_index[g][k] + n_vertices);
  }


  template <int dim>
  void
  NodalDilatationSystem<dim>::clear()
  {
    matrix = 0;
    rhs    = 0;
  }


  template <int dim>
  std::vector<std::tuple<unsigned int, double, Point<dim>>>
  NodalDilatationSystem<dim>::assemble(
    const VectorType                  &u,
    const materials::MaterialSet<dim> &materials,
    const FibreField<dim>             &fibres,
    const AffineConstraints<double>   &rows,
    const bool                         inhomogeneous,
    const bool                         jacobian,
    VectorType                        &residual,
    const Loads                       *loads)
  {
    Assert(!loads || jacobian, ExcInternalError());
    const auto        &cells = nodal.cells;
    const unsigned int n     = cells.size();
    if (jacobian)
      copy_dirichlet_lines(rows, relevant, augmented_rows);

    // F, J, J F^{-T} of every cell here, and the vertices' dilatations.
    std::vector<Tensor<2, dim>> F(n), cofactor(n);
    std::vector<double>         J(n);
    deformation(u, F, J, cofactor);
    const std::vector<double> sums = nodal.volume_times_J(J);

    // First pass, per owned cell: Psi-hat's derivatives at Jbar, and the
    // pressures pi_b they give the vertices (summed over the processes).
    struct Terms
    {
      bool                     defined  = false;
      double                   smallest = 0;
      MeanDilatationPoint<dim> psi;
    };
    std::vector<Terms> terms(n);
    parallel::apply_to_subranges(
      0U,
      n,
      [&](const unsigned int begin, const unsigned int end) {
        for (unsigned int e = begin; e < end; ++e)
          {
            const auto &cell = cells[e];
            if (!cell.owned)
              continue;
            const double theta    = nodal.vertex_average(cell, sums);
            const auto  &material = materials.material(cell.material_id);
            terms[e].defined
              = theta / J[e] > 0
                && (material.admits_inversion() || (J[e] > 0 && theta > 0));
            if (terms[e].defined)
              terms[e].psi = nodal.derivatives(
                cell, F[e], theta, materials, fibres, jacobian);
            else
              terms[e].smallest = std::min(J[e], theta);
          }
      },
      64);
    std::vector<std::tuple<unsigned int, double, Point<dim>>> inverted;
    std::vector<types::global_dof_index>                      where;
    std::vector<double>                                       what;
    for (unsigned int e = 0; e < n; ++e)
      if (cells[e].owned && !terms[e].defined)
        inverted.emplace_back(cells[e].active_index,
                              terms[e].smallest,
                              cells[e].centre);
      else if (cells[e].owned)
        for (unsigned int k = 0; k <= dim; ++k)
          {
            where.push_back(s_index[e][k]);
            what.push_back(terms[e].psi.phi_theta / (dim + 1));
          }
    pressure_sum = 0;
    pressure_sum.add(where, what);
    pressure_sum.compress(VectorOperation::add);
    pressure = pressure_sum;
    std::vector<const MeanDilatationPoint<dim> *> psi(n, nullptr);
    for (unsigned int e = 0; e < n; ++e)
      if (terms[e].defined)
        psi[e] = &terms[e].psi;
    if (jacobian)
      add_blocks(psi, J, cofactor, materials, loads, inhomogeneous);
    else
      add_residual(psi, J, cofactor, rows, residual);
    return inverted;
  }


  template <int dim>
  void
  NodalDilatationSystem<dim>::finish(const MatrixType *uu, VectorType &residual)
  {
    finish_augmented(matrix, rhs, uu, uu_row, uu_entry, residual);
  }


  template <int dim>
  void
  NodalDilatationSystem<dim>::solve(solvers::LinearSolver &solver,
                                    VectorType            &x,
                                    const VectorType      &b,
                                    const bool             refactorize)
  {
    solve_augmented(solver, matrix, rhs, owned, x, b, refactorize);
  }


  template class NodalDilatationSystem<1>;
  template class NodalDilatationSystem<2>;
  template class NodalDilatationSystem<3>;
} // namespace tissuefem::solid
