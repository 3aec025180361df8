// Solid's assembly through the lean kernel of linear simplices
// (linear_simplex_kernel.h): the kernel computes and adds the cells without
// constraints; the others go through AffineConstraints here, as in the
// general path of solid_assembly.cc. For the nodal dilatation the kernel
// gives the inertia and gravity, and the patches the elastic part.
#include <tissuefem/solid/solid.h>

#include <algorithm>

namespace tissuefem::solid
{
  template <int dim>
  bool
  Solid<dim>::uses_lean_kernel(const Request &request) const
  {
    // Body forces given as expressions and tractions need quadrature
    // points and faces: the general path integrates them.
    return lean
           && !(
             request.external
             && (body_force_present || !boundary_conditions.neumann.empty()));
  }


  template <int dim>
  void
  Solid<dim>::assemble_lean(const Request &request, VectorType &residual)
  {
    const unsigned int n = cache.n_dofs;
    discretization.initialize_assembly_vector(residual);
    // Jacobians into a formulation's own system (the nodal dilatation's)
    // take the inertia and gravity into the same cell blocks as the
    // elastic part (add_patch_terms()): the kernel has nothing left to do,
    // and the displacement matrix only the force contributions' terms
    // (without any, it is neither cleared nor added: 0.8 ms a step on
    // SOFA's liver).
    const bool loads_in_system = element->system_takes_loads()
                                 && request.jacobian && request.internal
                                 && !request.cells;
    const bool uu_block
      = request.jacobian
        && !(loads_in_system
             && (contributions.empty() || !request.contributions));
    if (uu_block)
      jacobian_matrix = 0;

    typename LinearSimplexKernel<dim>::Input input;
    // Where the formulation's elastic part is not the cells' own (the
    // nodal dilatation's patches), the kernel gives the inertia and loads,
    // add_patch_terms() the rest.
    const bool elastic = request.internal
                         && element->lean_kernel()
                              == formulations::Interface<dim>::LeanKernel::all;
    input.u = request.u && elastic ? request.u->trilinos_vector()[0] : nullptr;
    input.w = request.inertia ? request.inertia->trilinos_vector()[0] : nullptr;
    input.mass_jacobian_coefficient = request.mass_jacobian_coefficient;
    input.lumped_mass               = discretization.lumped_mass;
    boundary_conditions.set_time(request.time);
    input.gravity
      = boundary_conditions.load_factor * boundary_conditions.gravity;
    input.internal = elastic;
    input.external = request.external;
    input.jacobian = request.jacobian;
    input.cells    = request.cells;
    if (request.jacobian)
      {
        input.matrix_rows    = &access.row_values;
        input.matrix_row_of  = &access.row;
        input.matrix_entries = &access.entry;
      }
    // A lifting residual without the Jacobian (implicit_residual_lifting()
    // for a kept factorization): the matrices of the cells whose prescribed
    // values move, for the vector's share of the lifting below.
    const bool        lifting = !request.jacobian && request.inhomogeneous;
    std::vector<bool> lifted;
    if (lifting)
      {
        lifted               = moving_cells(*request.rows);
        input.jacobian       = true;
        input.jacobian_cells = &lifted;
      }
    const auto inverted_cells
      = loads_in_system ? std::vector<std::pair<unsigned int, double>>()
                        : lean->evaluate(input);

    std::vector<bool> inverted(cache.cells().size(), false);
    std::vector<std::tuple<unsigned int, double, Point<dim>>> report;
    for (const auto &[c, det] : inverted_cells)
      {
        inverted[c] = true;
        report.emplace_back(cache.cells()[c]->active_cell_index(),
                            det,
                            cache.cells()[c]->center());
      }

    // Forces without constraints (explicit steps, active regions) add a
    // cell's owned rows in place, not through AffineConstraints' index
    // lookups, and send the rest; cells in a fixed order, so the sum is
    // the same with any number of threads.
    const auto                          &index = cache.local_index;
    Vector<double>                       rhs(n);
    std::vector<types::global_dof_index> dofs(n);
    double                              *local = residual.trilinos_vector()[0];
    const auto                           add_cell = [&](const unsigned int c) {
      const double *vector = lean->cell_vector(c);
      const int    *row    = &access.row[c * n];
      bool          all    = true;
      for (unsigned int i = 0; i < n; ++i)
        if (row[index[i]] >= 0)
          local[row[index[i]]] += vector[i];
        else
          all = false;
      if (all)
        return;
      for (unsigned int i = 0; i < n; ++i)
        rhs[index[i]] = row[index[i]] >= 0 ? 0. : vector[i];
      std::copy(cache.dofs(c), cache.dofs(c) + n, dofs.begin());
      no_constraints.distribute_local_to_global(rhs, dofs, residual);
    };
    const bool unconstrained
      = !request.jacobian && request.rows == &no_constraints;

    // An active region (Jeffrey's node freezing): the cells the kernel
    // computed, in its order. Otherwise every owned row gathers the
    // residual entries of the direct cells (their matrices went into the
    // Jacobian as the kernel computed them), and the others follow.
    const bool active_region = request.cells && !request.jacobian;
    Assert(!active_region || unconstrained, ExcInternalError());
    if (active_region)
      for (const unsigned int c : lean->selected())
        {
          if (!inverted[c])
            add_cell(c);
        }
    else if (!loads_in_system)
      lean->add_direct(local);

    // Cells with constrained or non-owned dofs: element order, then the
    // request's constraints.
    const AffineConstraints<double> &rows = *request.rows;
    FullMatrix<double>               matrix(n, n);
    for (unsigned int c = 0;
         !active_region && !loads_in_system && c < cache.cells().size();
         ++c)
      {
        if (access.direct[c] || inverted[c]
            || (request.cells && !(*request.cells)[c]))
          continue;
        if (unconstrained)
          {
            add_cell(c);
            continue;
          }
        const double *vector = lean->cell_vector(c);
        for (unsigned int i = 0; i < n; ++i)
          rhs[index[i]] = vector[i];
        std::copy(cache.dofs(c), cache.dofs(c) + n, dofs.begin());
        if (request.jacobian)
          {
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                matrix(index[i], index[j]) = lean->cell_matrix(c, i, j);
            rows.distribute_local_to_global(matrix,
                                            rhs,
                                            dofs,
                                            jacobian_matrix,
                                            residual,
                                            request.inhomogeneous);
          }
        else
          rows.distribute_local_to_global(rhs, dofs, residual);
        // J_ij e_j out of row i for each moving prescribed dof j (what the
        // matrix form above does with the inhomogeneities).
        if (lifting && lifted[c])
          {
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                matrix(index[i], index[j]) = lean->cell_matrix(c, i, j);
            rows.distribute_local_to_global(
              rhs, dofs, dofs, residual, matrix, false);
          }
      }
    add_patch_terms(request, residual, report, loads_in_system);
    add_contributions(request, residual);

    residual.compress(VectorOperation::add);
    if (uu_block)
      jacobian_matrix.compress(VectorOperation::add);
    if (request.jacobian)
      element->finish_system(uu_block ? &jacobian_matrix : nullptr, residual);
    report_inversions(report);
  }


  template <int dim>
  std::vector<bool>
  Solid<dim>::moving_cells(const AffineConstraints<double> &rows) const
  {
    std::vector<bool> moving(cache.cells().size(), false);
    for (unsigned int c = 0; c < moving.size(); ++c)
      if (!access.direct[c])
        for (unsigned int i = 0; i < cache.n_dofs && !moving[c]; ++i)
          moving[c] = rows.is_inhomogeneously_constrained(cache.dofs(c)[i]);
    return moving;
  }


#define TISSUEFEM_INSTANTIATE(dim)                                        \
  template bool Solid<dim>::uses_lean_kernel(const Request &) const;      \
  template void Solid<dim>::assemble_lean(const Request &, VectorType &); \
  template std::vector<bool> Solid<dim>::moving_cells(                    \
    const AffineConstraints<double> &) const;
  TISSUEFEM_INSTANTIATE(1)
  TISSUEFEM_INSTANTIATE(2)
  TISSUEFEM_INSTANTIATE(3)
#undef TISSUEFEM_INSTANTIATE
} // namespace tissuefem::solid
