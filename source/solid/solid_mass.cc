// The solid's mass and energy operators: consistent and lumped mass,
// stored and kinetic energy (what explicit integrators and energy reports
// need; see solid.cc for assembly of forces and Jacobians).
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <tissuefem/solid/mean_dilatation.h>
#include <tissuefem/solid/quantities.h>
#include <tissuefem/solid/solid.h>

#include <cstring>
#include <limits>
#include <numeric>

#include <chrono>

namespace tissuefem::solid
{
  template <int dim>
  const MatrixType &
  Solid<dim>::mass_matrix()
  {
    if (mass)
      return *mass;
    // Unconstrained: explicit methods and energies need every row.
    TrilinosWrappers::SparsityPattern sparsity(discretization.locally_owned,
                                               discretization.locally_owned,
                                               discretization.locally_relevant,
                                               parallel_tools::communicator());
    DoFTools::make_sparsity_pattern(discretization.dof_handler,
                                    sparsity,
                                    no_constraints,
                                    true,
                                    Utilities::MPI::this_mpi_process(
                                      parallel_tools::communicator()));
    sparsity.compress();
    mass.emplace();
    mass->reinit(sparsity);
    const unsigned int                   n = cache.n_dofs, n_q = cache.n_q;
    const unsigned int                   n_scalar = cache.n_scalar;
    FullMatrix<double>                   cell_matrix(n, n);
    std::vector<types::global_dof_index> dofs(n);
    for (unsigned int c = 0; c < cache.cells().size(); ++c)
      {
        const double rho = materials.density(cache.cells()[c]->material_id());
        cell_matrix      = 0;
        for (unsigned int q = 0; q < n_q; ++q)
          for (unsigned int k = 0; k < n_scalar; ++k)
            for (unsigned int l = 0; l < n_scalar; ++l)
              {
                const double m = rho * cache.values[q * n_scalar + k]
                                 * cache.values[q * n_scalar + l]
                                 * cache.JxW(c)[q];
                for (unsigned int a = 0; a < dim; ++a)
                  cell_matrix(cache.local_index[k * dim + a],
                              cache.local_index[l * dim + a])
                    += m;
              }
        std::copy(cache.dofs(c), cache.dofs(c) + n, dofs.begin());
        no_constraints.distribute_local_to_global(cell_matrix, dofs, *mass);
      }
    mass->compress(VectorOperation::add);
    return *mass;
  }


  template <int dim>
  const VectorType &
  Solid<dim>::lumped_mass()
  {
    if (lumped)
      return *lumped;
    // Row sums of the consistent mass: since the shape functions sum to
    // one, row k sums to int rho N_k dV.
    lumped.emplace();
    discretization.initialize_assembly_vector(*lumped);
    const unsigned int                   n = cache.n_dofs, n_q = cache.n_q;
    const unsigned int                   n_scalar = cache.n_scalar;
    Vector<double>                       cell_vector(n);
    std::vector<types::global_dof_index> dofs(n);
    for (unsigned int c = 0; c < cache.cells().size(); ++c)
      {
        const double rho = materials.density(cache.cells()[c]->material_id());
        cell_vector      = 0;
        for (unsigned int q = 0; q < n_q; ++q)
          for (unsigned int k = 0; k < n_scalar; ++k)
            for (unsigned int a = 0; a < dim; ++a)
              cell_vector[cache.local_index[k * dim + a]]
                += rho * cache.values[q * n_scalar + k] * cache.JxW(c)[q];
        std::copy(cache.dofs(c), cache.dofs(c) + n, dofs.begin());
        no_constraints.distribute_local_to_global(cell_vector, dofs, *lumped);
      }
    lumped->compress(VectorOperation::add);
    return *lumped;
  }


  template <int dim>
  void
  Solid<dim>::mass_vmult(VectorType &dst, const VectorType &src)
  {
    // C^T M C src, C the hanging-node interpolation: the residual's
    // inertial term is assembled through the constraints, so products
    // that are subtracted from it or give its energy must be condensed
    // alike (without hanging nodes C = I).
    const bool  hanging_nodes = discretization.has_hanging_nodes;
    const auto &hanging       = discretization.hanging_node_constraints;
    VectorType  distributed;
    if (hanging_nodes)
      {
        distributed = src;
        hanging.distribute(distributed);
      }
    const VectorType &x = hanging_nodes ? distributed : src;
    if (discretization.lumped_mass)
      {
        dst = x;
        dst.scale(lumped_mass());
      }
    else
      {
        dst.reinit(x, true);
        mass_matrix().vmult(dst, x);
      }
    if (!hanging_nodes)
      return;
    // A hanging row goes to its parents' rows (deal.II's condense() reads
    // the hanging rows owned elsewhere from a ghosted copy).
    VectorType ghosted;
    discretization.initialize_vector(ghosted, true);
    ghosted = dst;
    hanging.condense(ghosted, dst);
  }


  template <int dim>
  double
  Solid<dim>::implicit_energy(const VectorType &u,
                              const VectorType &u_tilde,
                              const double      mass_coefficient,
                              const double      time)
  {
    // One ghosted copy serves the elements and the contributions.
    VectorType ghosted;
    discretization.initialize_vector(ghosted, true);
    make_ghosted(u, ghosted);
    double energy = stored_energy_with(ghosted, &time);
    if (!std::isfinite(energy))
      return energy;
    // Dead loads: the external work is f_ext . u, with hanging-node values
    // following their parents as in the stored energy.
    VectorType force, x(u);
    if (discretization.has_hanging_nodes)
      discretization.hanging_node_constraints.distribute(x);
    external_force(time, force);
    energy -= force * x;
    const auto start = std::chrono::steady_clock::now();
    for (const auto &contribution : contributions)
      energy += contribution->energy(ghosted, time);
    contribution_time
      += std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
           .count();
    if (mass_coefficient != 0)
      {
        // As the residual's inertial term M w, w = c (u - u_tilde), with
        // hanging-node values following their parents (mass_vmult()).
        VectorType difference(u), product(u);
        difference -= u_tilde;
        mass_vmult(product, difference);
        energy += 0.5 * mass_coefficient * (product * difference);
      }
    return energy;
  }


  template <int dim>
  double
  Solid<dim>::stored_energy(const VectorType &u) const
  {
    // The energy depends on the state alone (materials keep no state):
    // the same values give the same answer. Compared bit for bit on every
    // process (a NaN state matches itself).
    const double *values = u.trilinos_vector()[0];
    const auto    n      = static_cast<std::size_t>(u.locally_owned_size());
    std::lock_guard<std::mutex> guard(energy_memo.lock);
    const bool                  same_here
      = energy_memo.valid && energy_memo.u.size() == n
        && std::memcmp(values, energy_memo.u.data(), n * sizeof(double)) == 0;
    if (Utilities::MPI::min(same_here ? 1 : 0, parallel_tools::communicator())
        == 1)
      return energy_memo.energy;
    VectorType ghosted;
    discretization.initialize_vector(ghosted, true);
    make_ghosted(u, ghosted);
    energy_memo.energy = stored_energy_with(ghosted, nullptr);
    energy_memo.u.assign(values, values + n);
    energy_memo.valid = true;
    return energy_memo.energy;
  }


  template <int dim>
  double
  Solid<dim>::stored_energy_with(const VectorType &ghosted,
                                 const double     *carry_time) const
  {
    // From the cell cache, as assembly does: no FEValues per cell, so that
    // the per-step energy of explicit runs costs less than a force
    // evaluation.
    const unsigned int n_q = cache.n_q, n_scalar = cache.n_scalar;
    const unsigned int n      = cache.n_dofs;
    const double      *values = ghosted.trilinos_vector()[0];
    if (lean
        && element->lean_kernel()
             == formulations::Interface<dim>::LeanKernel::all)
      return Utilities::MPI::sum(lean->stored_energy(values),
                                 parallel_tools::communicator());
    double                      energy = 0;
    std::vector<Tensor<2, dim>> F(n_q);
    const auto                  deformation
      = element->deformation(context(), ghosted, carry_time);
    for (unsigned int c = 0; c < cache.cells().size(); ++c)
      {
        const auto &cell     = cache.cells()[c];
        const auto &material = materials.material(cell->material_id());
        // Where the formulation's F is constant per cell (the nodal
        // dilatation's linear simplex): one evaluation per cell unless the
        // fibre varies at the points (the line search asks for this energy
        // at every trial).
        const unsigned int n_e
          = element->constant_gradient() && !material.uses_fibres() ? 1 : n_q;
        for (unsigned int q = 0; q < n_e; ++q)
          {
            F[q] = unit_symmetric_tensor<dim>();
            for (unsigned int k = 0; k < n_scalar; ++k)
              {
                const Tensor<1, dim> &g = cache.gradient(c, q, k);
                for (unsigned int a = 0; a < dim; ++a)
                  {
                    const double u_ka
                      = values[access.ghost_index
                                 [c * n + cache.local_index[k * dim + a]]];
                    for (unsigned int b = 0; b < dim; ++b)
                      F[q][a][b] += u_ka * g[b];
                  }
              }
          }
        // The formulation's F (Fbar); where it is not defined (a cell
        // inverted, J and Jbar of different sign) the state is
        // inadmissible.
        if (!deformation->apply(cell, F, cache.JxW(c), n_e))
          {
            energy = std::numeric_limits<double>::infinity();
            break;
          }
        // Where the model is undefined (det F <= 0, no inversion) the state
        // is inadmissible, as assembly says by throwing.
        bool admissible = true;
        if (!material.admits_inversion())
          for (unsigned int q = 0; q < n_e; ++q)
            if (!(determinant(F[q]) > 0))
              admissible = false;
        if (!admissible)
          {
            energy = std::numeric_limits<double>::infinity();
            break;
          }
        for (unsigned int q = 0; q < n_e; ++q)
          {
            double psi = material.energy_density(
              F[q], fibre_field.at(cell->active_cell_index(), q));
            deformation->add_own_terms(cell, F[q], psi, nullptr);
            energy
              += psi
                 * (n_e == 1
                      ? std::accumulate(cache.JxW(c), cache.JxW(c) + n_q, 0.)
                      : cache.JxW(c)[q]);
          }
      }
    return Utilities::MPI::sum(energy, parallel_tools::communicator());
  }


  template <int dim>
  double
  Solid<dim>::kinetic_energy(const VectorType &v)
  {
    if (discretization.lumped_mass)
      {
        // C^T M C v . v: hanging-node values follow their parents, as
        // below.
        VectorType product(v);
        mass_vmult(product, v);
        return 0.5 * (product * v);
      }
    make_ghosted(v, ghosted_w);
    const unsigned int n_q = cache.n_q, n_scalar = cache.n_scalar;
    const unsigned int n      = cache.n_dofs;
    const double      *values = ghosted_w.trilinos_vector()[0];
    if (lean)
      return Utilities::MPI::sum(lean->kinetic_energy(values),
                                 parallel_tools::communicator());
    double energy = 0;
    for (unsigned int c = 0; c < cache.cells().size(); ++c)
      {
        const double rho = materials.density(cache.cells()[c]->material_id());
        for (unsigned int q = 0; q < n_q; ++q)
          {
            Tensor<1, dim> velocity;
            for (unsigned int k = 0; k < n_scalar; ++k)
              for (unsigned int a = 0; a < dim; ++a)
                velocity[a]
                  += cache.values[q * n_scalar + k]
                     * values[access.ghost_index
                                [c * n + cache.local_index[k * dim + a]]];
            energy += 0.5 * rho * velocity.norm_square() * cache.JxW(c)[q];
          }
      }
    return Utilities::MPI::sum(energy, parallel_tools::communicator());
  }


  template <int dim>
  const std::vector<std::vector<types::global_dof_index>> &
  Solid<dim>::column_groups()
  {
    if (!groups.empty())
      return groups;
    // Every process holds every cell (shared triangulation), so every
    // process colours the whole graph alike. Dofs j and k conflict when a
    // row couples to both, i.e. when they lie in cells that share a dof:
    // greedy colouring over neighbours of neighbours, in index order.
    const auto                   &dh = discretization.dof_handler;
    const types::global_dof_index n  = dh.n_dofs();
    std::vector<std::vector<types::global_dof_index>> neighbours(n);
    std::vector<types::global_dof_index> dofs(dh.get_fe().n_dofs_per_cell());
    for (const auto &cell : dh.active_cell_iterators())
      {
        cell->get_dof_indices(dofs);
        for (const auto i : dofs)
          neighbours[i].insert(neighbours[i].end(), dofs.begin(), dofs.end());
      }
    for (auto &list : neighbours)
      {
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
      }
    std::vector<int>          colour(n, -1);
    std::vector<unsigned int> seen_by;
    for (types::global_dof_index j = 0; j < n; ++j)
      {
        for (const auto i : neighbours[j])
          for (const auto k : neighbours[i])
            if (colour[k] >= 0)
              {
                if (seen_by.size() <= static_cast<unsigned int>(colour[k]))
                  seen_by.resize(colour[k] + 1, n);
                seen_by[colour[k]] = j;
              }
        unsigned int c = 0;
        while (c < seen_by.size() && seen_by[c] == j)
          ++c;
        colour[j] = c;
        if (groups.size() <= c)
          groups.resize(c + 1);
        groups[c].push_back(j);
      }
    return groups;
  }


  template <int dim>
  bool
  Solid<dim>::has_hanging_nodes() const
  {
    return discretization.has_hanging_nodes;
  }


  // The class is instantiated in solid.cc; these members here.
#define TISSUEFEM_INSTANTIATE(dim)                                          \
  template const MatrixType &Solid<dim>::mass_matrix();                     \
  template const VectorType &Solid<dim>::lumped_mass();                     \
  template void   Solid<dim>::mass_vmult(VectorType &, const VectorType &); \
  template double Solid<dim>::stored_energy(const VectorType &) const;      \
  template double Solid<dim>::stored_energy_with(const VectorType &,        \
                                                 const double *) const;     \
  template double Solid<dim>::kinetic_energy(const VectorType &);           \
  template double Solid<dim>::implicit_energy(const VectorType &,           \
                                              const VectorType &,           \
                                              const double,                 \
                                              const double);                \
  template const std::vector<std::vector<types::global_dof_index>>          \
               &Solid<dim>::column_groups();                                \
  template bool Solid<dim>::has_hanging_nodes() const;
  TISSUEFEM_INSTANTIATE(1)
  TISSUEFEM_INSTANTIATE(2)
  TISSUEFEM_INSTANTIATE(3)
#undef TISSUEFEM_INSTANTIATE
} // namespace tissuefem::solid
