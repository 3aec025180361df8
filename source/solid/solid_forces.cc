// The solid's force operators: internal forces (all cells or an active
// region), the cells and dofs an active region touches, external loads,
// reaction and held forces (see solid.cc for the assembly they call).
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>

#include <tissuefem/solid/solid.h>

#include <algorithm>

namespace tissuefem::solid
{
  template <int dim>
  void
  Solid<dim>::internal_force(const VectorType &u, VectorType &force)
  {
    make_ghosted(u, ghosted_u);
    Request request;
    request.u             = &ghosted_u;
    request.external      = false;
    request.rows          = &no_constraints;
    request.contributions = false;
    assemble(request, force);
  }


  template <int dim>
  void
  Solid<dim>::internal_force(const VectorType &u,
                             const double      time,
                             VectorType       &force)
  {
    make_ghosted(u, ghosted_u);
    Request request;
    request.u        = &ghosted_u;
    request.time     = time;
    request.external = false;
    request.rows     = &no_constraints;
    assemble(request, force);
  }


  template <int dim>
  double
  Solid<dim>::contribution_frequency_bound()
  {
    if (contributions.empty())
      return 0;
    VectorType sums;
    discretization.initialize_assembly_vector(sums);
    for (const auto &contribution : contributions)
      contribution->add_stiffness_bound(sums);
    sums.compress(VectorOperation::add);
    const VectorType &mass  = lumped_mass();
    double            worst = 0;
    for (const auto i : sums.locally_owned_elements())
      if (!discretization.constraints.is_constrained(i) && mass[i] > 0)
        worst = std::max(worst, sums[i] / mass[i]);
    return Utilities::MPI::max(worst, parallel_tools::communicator());
  }


  template <int dim>
  void
  Solid<dim>::internal_force_on(const VectorType        &u,
                                const std::vector<bool> &active_cells,
                                VectorType              &force)
  {
    AssertDimension(active_cells.size(), cache.cells().size());
    make_ghosted(u, ghosted_u);
    Request request;
    request.u             = &ghosted_u;
    request.external      = false;
    request.rows          = &no_constraints;
    request.cells         = &active_cells;
    request.contributions = false;
    assemble(request, force);
  }


  template <int dim>
  std::vector<bool>
  Solid<dim>::cells_touching(const VectorType &mask)
  {
    make_ghosted(mask, ghosted_w);
    // Few marked entries: from them to their cells, so that the work
    // grows with the marked part of the mesh. Many: each cell stops at
    // its first marked entry.
    const double      *values    = ghosted_w.trilinos_vector()[0];
    const unsigned int n_entries = access.cells_of_begin.size() - 1;
    const auto         n_marked  = std::count_if(values,
                                        values + n_entries,
                                        [](const double x) { return x != 0; });
    std::vector<bool>  active(cache.cells().size(), false);
    if (8 * n_marked < n_entries)
      for (unsigned int g = 0; g < n_entries; ++g)
        {
          if (values[g] != 0)
            for (unsigned int s = access.cells_of_begin[g];
                 s < access.cells_of_begin[g + 1];
                 ++s)
              active[access.cells_of[s]] = true;
        }
    else
      for (unsigned int c = 0; c < active.size(); ++c)
        for (unsigned int i = 0; i < cache.n_dofs; ++i)
          if (values[access.ghost_index[c * cache.n_dofs + i]] != 0)
            {
              active[c] = true;
              break;
            }
    return active;
  }


  template <int dim>
  void
  Solid<dim>::mark_dofs_of(const std::vector<bool> &cells, VectorType &mask)
  {
    AssertDimension(cells.size(), cache.cells().size());
    // Active regions call this every step: owned dofs are marked in place;
    // dofs owned by other processes are sent as counts, added there.
    const unsigned int n = cache.n_dofs;
    initialize_vector(mask);
    double                              *to = mask.trilinos_vector()[0];
    std::vector<types::global_dof_index> remote;
    for (unsigned int c = 0; c < cells.size(); ++c)
      {
        if (!cells[c])
          continue;
        for (unsigned int i = 0; i < n; ++i)
          {
            const int row = access.row[c * n + i];
            if (row >= 0)
              to[row] = 1.;
            else
              remote.push_back(cache.dofs(c)[i]);
          }
      }
    if (parallel_tools::n_processes() == 1)
      return;
    VectorType counts;
    discretization.initialize_assembly_vector(counts);
    const std::vector<double> ones(remote.size(), 1.);
    counts.add(remote, ones);
    counts.compress(VectorOperation::add);
    const double *from = counts.trilinos_vector()[0];
    for (unsigned int i = 0; i < mask.locally_owned_size(); ++i)
      if (from[i] > 0)
        to[i] = 1.;
  }


  template <int dim>
  void
  Solid<dim>::external_force(const double time, VectorType &force)
  {
    // Most surgical scenes have no load but the tool: skip the pass.
    if (!body_force_present && boundary_conditions.neumann.empty()
        && boundary_conditions.gravity.norm() == 0)
      {
        initialize_vector(force);
        return;
      }
    Request request;
    request.internal = false;
    request.time     = time;
    request.rows     = &no_constraints;
    assemble(request, force);
    force *= -1.;
  }


  template <int dim>
  std::vector<double>
  Solid<dim>::reaction_forces(
    const VectorType                      &u,
    const VectorType                      &acceleration,
    const double                           time,
    const RayleighDamping                 &damping,
    const std::vector<types::boundary_id> &boundary_ids)
  {
    std::vector<double> forces(boundary_ids.size() * dim, 0.);
    if (boundary_ids.empty())
      return forces;
    VectorType residual;
    unconstrained_residual(u, acceleration, time, damping, residual);
    for (unsigned int b = 0; b < boundary_ids.size(); ++b)
      for (unsigned int c = 0; c < dim; ++c)
        {
          std::vector<bool> mask(dim, false);
          mask[c] = true;
          IndexSet dofs
            = DoFTools::extract_boundary_dofs(discretization.dof_handler,
                                              ComponentMask(mask),
                                              {boundary_ids[b]});
          dofs = dofs & discretization.locally_owned;
          for (const auto dof : dofs)
            forces[b * dim + c] += residual[dof];
        }
    Utilities::MPI::sum(forces, parallel_tools::communicator(), forces);
    return forces;
  }


  template <int dim>
  void
  Solid<dim>::unconstrained_residual(const VectorType      &u,
                                     const VectorType      &acceleration,
                                     const double           time,
                                     const RayleighDamping &damping,
                                     VectorType            &residual)
  {
    // With w = a + alpha v: R = M w + r(u), and with R_old = M w + r(u_old)
    // the damped residual M a + r(u) + f_d is R + beta/h (R - R_old).
    if (damping.alpha != 0)
      {
        VectorType w(acceleration);
        w.add(damping.alpha / damping.step, u);
        w.add(-damping.alpha / damping.step, damping.u_old);
        make_ghosted(w, ghosted_w);
      }
    else
      make_ghosted(acceleration, ghosted_w);
    make_ghosted(u, ghosted_u);
    Request request;
    request.u       = &ghosted_u;
    request.inertia = &ghosted_w;
    request.time    = time;
    request.rows    = &no_constraints;
    assemble(request, residual);
    if (damping.beta == 0)
      return;
    VectorType old_residual;
    make_ghosted(damping.u_old, ghosted_u);
    assemble(request, old_residual);
    const double ratio = damping.beta / damping.step;
    residual.sadd(1 + ratio, -ratio, old_residual);
  }


  template <int dim>
  std::vector<double>
  Solid<dim>::held_force(const VectorType      &u,
                         const VectorType      &acceleration,
                         const double           time,
                         const RayleighDamping &damping)
  {
    std::vector<double> force(dim, 0.);
    if (!held)
      return force;
    VectorType residual;
    unconstrained_residual(u, acceleration, time, damping, residual);
    for (const auto &[dof, vertex, component] : held_dofs)
      if (discretization.locally_owned.is_element(dof))
        force[component] -= residual[dof];
    Utilities::MPI::sum(force, parallel_tools::communicator(), force);
    return force;
  }


  template <int dim>
  bool
  Solid<dim>::changes_with_time() const
  {
    // A tool's trajectory moves what it holds (a held tool standing still
    // is rare enough not to be told apart).
    return boundary_conditions.changes_with_time() || held.has_value()
           || std::any_of(contributions.begin(),
                          contributions.end(),
                          [](const auto &c) { return c->changes_with_time(); });
  }


  template <int dim>
  std::optional<double>
  Solid<dim>::load_factor(const double time) const
  {
    if (!boundary_conditions.load_factor_names_time())
      return std::nullopt;
    return boundary_conditions.load_factor_at(time);
  }


  template <int dim>
  double
  Solid<dim>::load_factor_at(const double time) const
  {
    return boundary_conditions.load_factor_at(time);
  }


  template <int dim>
  Operators::LoadHistory
  Solid<dim>::load_history() const
  {
    if (!boundary_conditions.has_loads())
      return LoadHistory::none;
    return boundary_conditions.loads_name_time() ? LoadHistory::changing
                                                 : LoadHistory::constant;
  }


  template <int dim>
  void
  Solid<dim>::hold_load_factor(const std::optional<double> factor)
  {
    boundary_conditions.held_load_factor = factor;
  }


  // The class is instantiated in solid.cc; these members here.
#define TISSUEFEM_INSTANTIATE(dim)                                               \
  template void   Solid<dim>::internal_force(const VectorType &, VectorType &);  \
  template void   Solid<dim>::internal_force(const VectorType &,                 \
                                           const double,                       \
                                           VectorType &);                      \
  template double Solid<dim>::contribution_frequency_bound();                    \
  template void   Solid<dim>::internal_force_on(const VectorType &,              \
                                              const std::vector<bool> &,       \
                                              VectorType &);                   \
  template std::vector<bool> Solid<dim>::cells_touching(const VectorType &);     \
  template void              Solid<dim>::mark_dofs_of(const std::vector<bool> &, \
                                         VectorType &);             \
  template void Solid<dim>::external_force(const double, VectorType &);          \
  template std::vector<double> Solid<dim>::reaction_forces(                      \
    const VectorType &,                                                          \
    const VectorType &,                                                          \
    const double,                                                                \
    const RayleighDamping &,                                                     \
    const std::vector<types::boundary_id> &);                                    \
  template void Solid<dim>::unconstrained_residual(const VectorType &,           \
                                                   const VectorType &,           \
                                                   const double,                 \
                                                   const RayleighDamping &,      \
                                                   VectorType &);                \
  template std::vector<double> Solid<dim>::held_force(                           \
    const VectorType &, const VectorType &, double, const RayleighDamping &);    \
  template bool                  Solid<dim>::changes_with_time() const;          \
  template std::optional<double> Solid<dim>::load_factor(const double) const;    \
  template double                Solid<dim>::load_factor_at(const double) const; \
  template Operators::LoadHistory Solid<dim>::load_history() const;              \
  template void Solid<dim>::hold_load_factor(const std::optional<double>);
  TISSUEFEM_INSTANTIATE(1)
  TISSUEFEM_INSTANTIATE(2)
  TISSUEFEM_INSTANTIATE(3)
#undef TISSUEFEM_INSTANTIATE
} // namespace tissuefem::solid
