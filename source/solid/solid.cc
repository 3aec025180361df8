#include <deal.II/base/memory_consumption.h>
#include <deal.II/base/work_stream.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/numerics/vector_tools.h>

#include <tissuefem/geometry/distribution.h>
#include <tissuefem/materials/kinematics.h>
#include <tissuefem/materials/tangent_projection.h>
#include <tissuefem/solid/matrix_rows.h>
#include <tissuefem/solid/quantities.h>
#include <tissuefem/solid/solid.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_FEVector.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <sstream>

#include <chrono>

namespace tissuefem::solid
{


  template <int dim>
  Solid<dim>::Solid(Discretization<dim>               &discretization,
                    const materials::MaterialSet<dim> &materials,
                    boundary::BoundaryConditions<dim> &boundary_conditions,
                    std::unique_ptr<formulations::Interface<dim>> formulation)
      : discretization(discretization)
      , materials(materials)
      , boundary_conditions(boundary_conditions)
      , element(std::move(formulation))
      , body_force_present(!boundary_conditions.body_force_is_zero)
  {
    no_constraints.close();
    if (!element)
      {
        ParameterHandler defaults;
        formulations::declare_parameters(defaults);
        element = formulations::create<dim>(materials.formulation(), defaults);
      }
    element->check(discretization, materials);
    setup();
  }


  template <int dim>
  void
  Solid<dim>::setup()
  {
    signals.about_to_change();
    discretization.distribute(&boundary_conditions,
                              held ? &held->vertices : nullptr);
    const auto &dof_handler = discretization.dof_handler;
    mass.reset();
    lumped.reset();
    groups.clear();
    held_dofs.clear();
    if (held)
      held_dofs = held_vertex_dofs(dof_handler,
                                   held->vertices,
                                   discretization.locally_relevant);
    cache.build(discretization, body_force_present);
    energy_memo.valid = false;
    find_dirichlet_points();
    // Asked for every explicit step; the mesh's extent changes only here.
    diameter
      = geometry::diameter(discretization.dof_handler.get_triangulation());
    fibre_field.build(discretization, materials, element->fibre_per_cell());
    element->setup(context());
    discretization.initialize_vector(ghosted_u, true);
    discretization.initialize_vector(ghosted_w, true);
    lean.reset();
    build_jacobian_matrix(false);
    if (discretization.lean_kernel
        && element->lean_kernel()
             != formulations::Interface<dim>::LeanKernel::none
        && LinearSimplexKernel<dim>::applies(discretization, cache))
      {
        lean = std::make_unique<LinearSimplexKernel<dim>>();
        lean->build(cache,
                    fibre_field,
                    materials,
                    access.ghost_index,
                    access.direct,
                    access.row,
                    discretization.locally_owned.n_elements());
      }
    signals.changed();
  }


  template <int dim>
  void
  Solid<dim>::build_jacobian_matrix(const bool wide)
  {
    TrilinosWrappers::SparsityPattern sparsity(discretization.locally_owned,
                                               discretization.locally_owned,
                                               discretization.locally_relevant,
                                               parallel_tools::communicator());
    DoFTools::make_sparsity_pattern(discretization.dof_handler,
                                    sparsity,
                                    discretization.constraints,
                                    false,
                                    Utilities::MPI::this_mpi_process(
                                      parallel_tools::communicator()));
    element->build_system(context(),
                          solves_only_through_operators,
                          wide,
                          sparsity);
    wide_layout = element->couples_patches() && !element->has_system() && wide;
    sparsity.compress();
    jacobian_matrix.reinit(sparsity);
    build_direct_access();
  }


  template <int dim>
  MatrixType &
  Solid<dim>::jacobian()
  {
    AssertThrow(!element->has_system(),
                ExcMessage("The formulation keeps its Jacobian as a system "
                           "of its own (the nodal dilatation's, "
                           "nodal_dilatation_system.h): solve with "
                           "solve_jacobian()."));
    return jacobian_matrix;
  }


  template <int dim>
  void
  Solid<dim>::solve_only_through_operators(const bool             only,
                                           solvers::LinearSolver &solver)
  {
    const bool wanted = only && solver.direct();
    element->check_solving(wanted);
    if (wanted == solves_only_through_operators)
      return;
    solves_only_through_operators = wanted;
    if (!element->couples_patches())
      return;
    solver.reset();
    build_jacobian_matrix(false);
  }


  template <int dim>
  void
  Solid<dim>::solve_jacobian(solvers::LinearSolver &solver,
                             VectorType            &x,
                             const VectorType      &b,
                             const bool             refactorize,
                             const double           relative_tolerance,
                             const bool             from_guess)
  {
    // A formulation's own system is solved directly: no guess to start
    // from.
    if (element->has_system())
      element->solve_system(solver, x, b, refactorize);
    else
      solver.solve(
        jacobian_matrix, x, b, refactorize, relative_tolerance, from_guess);
  }


  template <int dim>
  std::vector<std::pair<std::string, std::size_t>>
  Solid<dim>::memory_parts() const
  {
    using MemoryConsumption::memory_consumption;
    const auto &d = discretization;
    std::size_t caches
      = cache.memory_consumption() + (lean ? lean->memory_consumption() : 0)
        + element->memory_consumption() + memory_consumption(access.ghost_index)
        + access.direct.capacity() / 8 + memory_consumption(access.row)
        + memory_consumption(access.entry)
        + memory_consumption(access.cells_of_begin)
        + memory_consumption(access.cells_of)
        + memory_consumption(access.row_values);
    return {{"mesh", d.dof_handler.get_triangulation().memory_consumption()},
            {"numbering",
             d.dof_handler.memory_consumption()
               + d.constraints.memory_consumption()
               + d.hanging_node_constraints.memory_consumption()
               + d.locally_owned.memory_consumption()
               + d.locally_relevant.memory_consumption()},
            {"assembly caches", caches},
            {"Jacobian", jacobian_matrix.memory_consumption()},
            {"mass matrix",
             (mass ? mass->memory_consumption() : 0)
               + (lumped ? lumped->memory_consumption() : 0)}};
  }


  template <int dim>
  void
  Solid<dim>::build_direct_access()
  {
    const unsigned int n       = cache.n_dofs;
    const unsigned int n_cells = cache.cells().size();
    const auto        &owned   = discretization.locally_owned;
    const auto        &ghosts  = ghosted_u.trilinos_vector().Map();
    access.ghost_index.resize(n_cells * n);
    access.direct.assign(n_cells, false);
    access.row.assign(n_cells * n, -1);
    access.entry.assign(n_cells * n * n, 0);
    access.row_values = row_value_pointers(jacobian_matrix);
    for (unsigned int c = 0; c < n_cells; ++c)
      {
        const auto *dofs   = cache.dofs(c);
        bool        direct = true;
        for (unsigned int i = 0; i < n; ++i)
          {
            access.ghost_index[c * n + i] = ghosts.LID(
              static_cast<TrilinosWrappers::types::int_type>(dofs[i]));
            direct = direct && owned.is_element(dofs[i])
                     && !discretization.constraints.is_constrained(dofs[i]);
            if (owned.is_element(dofs[i]))
              access.row[c * n + i] = owned.index_within_set(dofs[i]);
          }
        for (unsigned int i = 0; direct && i < n; ++i)
          for (unsigned int j = 0; direct && j < n; ++j)
            {
              const int position
                = entry_in_row(jacobian_matrix, access.row[c * n + i], dofs[j]);
              // entry_in_row() throws where the entry is missing.
              direct                            = position < (1 << 16);
              access.entry[(c * n + i) * n + j] = position;
            }
        access.direct[c] = direct;
        // The lean kernel adds direct cells into the rows as it computes
        // them and keeps the others' matrices, as it was built.
        Assert(!lean || lean->keeps_matrix(c) == !direct, ExcInternalError());
      }
    // Cells by ghosted entry, for active regions (cells_touching).
    access.cells_of_begin.assign(ghosts.NumMyElements() + 1, 0);
    for (const int g : access.ghost_index)
      ++access.cells_of_begin[g + 1];
    for (unsigned int g = 0; g + 1 < access.cells_of_begin.size(); ++g)
      access.cells_of_begin[g + 1] += access.cells_of_begin[g];
    access.cells_of.resize(access.ghost_index.size());
    std::vector<unsigned int> next(access.cells_of_begin.begin(),
                                   access.cells_of_begin.end() - 1);
    for (unsigned int c = 0; c < n_cells; ++c)
      for (unsigned int i = 0; i < n; ++i)
        access.cells_of[next[access.ghost_index[c * n + i]]++] = c;
  }


  template <int dim>
  double
  Solid<dim>::length_scale() const
  {
    return diameter;
  }


  template <int dim>
  void
  Solid<dim>::initialize_vector(VectorType &v) const
  {
    discretization.initialize_vector(v);
  }


  template <int dim>
  void
  Solid<dim>::make_ghosted(const VectorType &u, VectorType &ghosted) const
  {
    // Hanging-node values follow their parents; a state may hold stale
    // ones (Newton updates are zero there), so they are set here.
    if (!discretization.has_hanging_nodes)
      {
        ghosted = u;
        return;
      }
    VectorType owned(u);
    discretization.hanging_node_constraints.distribute(owned);
    ghosted = owned;
  }


  template <int dim>
  typename Solid<dim>::Request
  Solid<dim>::implicit_request(const VectorType &u,
                               const VectorType &u_tilde,
                               const double      mass_coefficient,
                               const double      time)
  {
    make_ghosted(u, ghosted_u);
    Request request;
    request.u = &ghosted_u;
    if (mass_coefficient != 0)
      {
        // The inertial term c M (u - u_tilde) is M w with w = c (u -
        // u_tilde), its hanging-node values from their parents (Newton
        // leaves them stale in u).
        VectorType w(u);
        w -= u_tilde;
        w *= mass_coefficient;
        make_ghosted(w, ghosted_w);
        request.inertia = &ghosted_w;
      }
    request.mass_jacobian_coefficient = mass_coefficient;
    request.time                      = time;
    request.carry                     = true;
    return request;
  }


  template <int dim>
  void
  Solid<dim>::implicit_residual(const VectorType &u,
                                const VectorType &u_tilde,
                                const double      mass_coefficient,
                                const double      time,
                                VectorType       &residual,
                                const bool        with_jacobian)
  {
    Request request  = implicit_request(u, u_tilde, mass_coefficient, time);
    request.jacobian = with_jacobian;
    request.rows     = &discretization.constraints;
    assemble(request, residual);
  }


  template <int dim>
  void
  Solid<dim>::begin_step(const VectorType &u, const double time)
  {
    if (!contributions.empty())
      {
        make_ghosted(u, ghosted_u);
        for (const auto &contribution : contributions)
          contribution->begin_step(ghosted_u, time);
      }
  }


  template <int dim>
  void
  Solid<dim>::accept_step(const VectorType &u, const double time)
  {
    if (contributions.empty())
      return;
    make_ghosted(u, ghosted_u);
    for (const auto &contribution : contributions)
      contribution->accept_step(ghosted_u, time);
  }


  template <int dim>
  Augmentation
  Solid<dim>::augment(const VectorType  &u,
                      const double       time,
                      const unsigned int update,
                      std::string       &message)
  {
    if (contributions.empty())
      return Augmentation::satisfied;
    make_ghosted(u, ghosted_u);
    auto       result = Augmentation::satisfied;
    const auto start  = std::chrono::steady_clock::now();
    // Counted on every way out.
    struct Clock
    {
      double                                      &total;
      const std::chrono::steady_clock::time_point &start;
      ~Clock()
      {
        total += std::chrono::duration<double>(std::chrono::steady_clock::now()
                                               - start)
                   .count();
      }
    } clock{contribution_time, start};
    for (const auto &contribution : contributions)
      {
        std::string why;
        const auto status = contribution->augment(ghosted_u, time, update, why);
        if (status == Augmentation::failed)
          {
            message = why;
            return status;
          }
        if (status == Augmentation::again)
          result = status;
      }
    return result;
  }


  template <int dim>
  bool
  Solid<dim>::implicit_residual_lifting(const VectorType &u,
                                        const VectorType &u_tilde,
                                        const double      mass_coefficient,
                                        const double      time,
                                        VectorType       &residual,
                                        const bool        with_jacobian)
  {
    Request request = implicit_request(u, u_tilde, mass_coefficient, time);
    // deal.II adds -J_ij e_j to row i for an inhomogeneity e_j of a
    // constrained dof j, and diag_j e_j to row j; with e = u - g that is
    // R + J d and -diag d for d = g - u.
    const auto &hanging = discretization.hanging_node_constraints;
    lifting_constraints.clear();
    lifting_constraints.reinit(discretization.locally_relevant);
    lifting_constraints.merge(hanging);
    for (const auto &[dof, value] : dirichlet_values(time))
      if (discretization.locally_relevant.is_element(dof)
          && !hanging.is_constrained(dof))
        {
          lifting_constraints.add_line(dof);
          lifting_constraints.set_inhomogeneity(dof, ghosted_u[dof] - value);
        }
    lifting_constraints.close();
    // Only the lean kernel lifts from the moving cells' own matrices; a
    // formulation's own system, its patches and the force contributions
    // (contact) add their terms through the Jacobian.
    request.jacobian = with_jacobian || !uses_lean_kernel(request)
                       || element->has_system()
                       || element->lean_kernel()
                            != formulations::Interface<dim>::LeanKernel::all
                       || !contributions.empty();
    request.rows          = &lifting_constraints;
    request.inhomogeneous = true;
    assemble(request, residual);
    // deal.II 9.4 adds |K_jj| of each cell to a constrained diagonal but
    // K_jj e_j to its row of the right-hand side: where some cell's K_jj <
    // 0 (a compressed St Venant-Kirchhoff cell) the update would miss the
    // prescribed value. Each such row is diag e_j, so that it gives d_j.
    const MatrixType &matrix
      = element->system_matrix() ? *element->system_matrix() : jacobian_matrix;
    for (const auto &line : lifting_constraints.get_lines())
      if (line.entries.empty()
          && discretization.locally_owned.is_element(line.index))
        residual[line.index]
          = matrix.diag_element(line.index) * line.inhomogeneity;
    residual.compress(VectorOperation::insert);
    return request.jacobian;
  }


  template class Solid<1>;
  template class Solid<2>;
  template class Solid<3>;
} // namespace tissuefem::solid
