#include <deal.II/base/exceptions.h>
#include <deal.II/base/parallel.h>
#include <deal.II/lac/trilinos_index_access.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/materials/kinematics.h>
#include <tissuefem/solid/augmented_system.h>
#include <tissuefem/solid/matrix_rows.h>
#include <tissuefem/solid/nodal_pressure.h>

#include <algorithm>
#include <cstring>

namespace tissuefem::solid
{
  namespace
  {
    /// The P1 mass of a simplex of volume @p V between its nodes a and b,
    /// and the same with the shape functions' cell means (Pi_0 N_a = 1 /
    /// (d + 1)): the stabilization's M - M0 (Dohrmann and Bochev 2004,
    /// eq 3.4).
    template <int dim>
    double
    pressure_entry(const double V,
                   const bool   same,
                   const double lambda,
                   const double mu,
                   const double alpha)
    {
      const double m  = V * (same ? 2. : 1.) / ((dim + 1) * (dim + 2));
      const double m0 = V / ((dim + 1) * (dim + 1));
      return m / lambda + alpha * (m - m0) / mu;
    }
  } // namespace


  template <int dim>
  NodalPressure<dim>::NodalPressure(
    const Discretization<dim>         &discretization,
    const NodalDilatation<dim>        &cells,
    const materials::MaterialSet<dim> &materials,
    const double                       stabilization)
      : nodal(cells)
      , stabilization(stabilization)
      , control(1, 0.)
  {
    const MPI_Comm comm = parallel_tools::communicator();
    n_u                 = discretization.n_dofs();
    n_active_cells
      = discretization.dof_handler.get_triangulation().n_active_cells();
    owned_p    = vertex_set(discretization.locally_owned, dim);
    relevant_p = vertex_set(discretization.locally_relevant, dim);
    // The Newton system's unknowns: the displacement's, then p.
    owned    = with_vertex_unknowns(discretization.locally_owned, dim, 1);
    relevant = with_vertex_unknowns(discretization.locally_relevant, dim, 1);

    for (unsigned int g = 0; g < nodal.cells.size(); ++g)
      if (nodal.cells[g].owned)
        {
          const auto &cell = nodal.cells[g];
          owned_cells.push_back(g);
          std::array<types::global_dof_index, dim + 1> v;
          for (unsigned int i = 0; i < cell.dofs.size(); ++i)
            if (cell.node_component[i].second == 0)
              v[cell.node_component[i].first] = cell.dofs[i] / dim;
          vertex.push_back(v);
          const auto part
            = materials.material(cell.material_id).volumetric_part(1.);
          AssertThrow(part.lambda > 0 && part.mu > 0, ExcInternalError());
          moduli.push_back({{part.lambda, part.mu}});
        }

    // A, fixed per mesh: the reference cells' pressure mass and
    // stabilization.
    TrilinosWrappers::SparsityPattern sparsity(owned_p,
                                               owned_p,
                                               relevant_p,
                                               comm);
    for (const auto &v : vertex)
      for (unsigned int a = 0; a <= dim; ++a)
        for (unsigned int b = 0; b <= dim; ++b)
          sparsity.add(v[a], v[b]);
    sparsity.compress();
    A.reinit(sparsity);
    FullMatrix<double>                   local(dim + 1, dim + 1);
    std::vector<types::global_dof_index> indices(dim + 1);
    for (unsigned int o = 0; o < owned_cells.size(); ++o)
      {
        const double V = nodal.cells[owned_cells[o]].volume;
        for (unsigned int a = 0; a <= dim; ++a)
          {
            indices[a] = vertex[o][a];
            for (unsigned int b = 0; b <= dim; ++b)
              local(a, b) = pressure_entry<dim>(
                V, a == b, moduli[o][0], moduli[o][1], stabilization);
          }
        A.add(indices, local);
      }
    A.compress(VectorOperation::add);
    factorization = std::make_unique<TrilinosWrappers::SolverDirect>(
      control, TrilinosWrappers::SolverDirect::AdditionalData(false));
    factorization->initialize(A);
    b.reinit(owned_p, relevant_p, comm, true);
    owned_b.reinit(owned_p, comm);
    p.reinit(owned_p, comm);
    pressure.reinit(owned_p, relevant_p, comm);
    const auto &ghosts = pressure.trilinos_vector().Map();
    for (const auto &v : vertex)
      for (unsigned int a = 0; a <= dim; ++a)
        pressure_index.push_back(
          ghosts.LID(static_cast<TrilinosWrappers::types::int_type>(v[a])));
    const unsigned int n_e
      = nodal.cells.empty() ? 0 : nodal.cells[0].dofs.size();
    residual_row.assign(owned_cells.size() * n_e, -1);
    for (unsigned int o = 0; o < owned_cells.size(); ++o)
      {
        const auto &dofs = nodal.cells[owned_cells[o]].dofs;
        bool        free = true;
        for (const auto i : dofs)
          free = free && discretization.locally_owned.is_element(i)
                 && !discretization.constraints.is_constrained(i);
        if (free)
          for (unsigned int i = 0; i < n_e; ++i)
            residual_row[o * n_e + i]
              = discretization.locally_owned.index_within_set(dofs[i]);
      }
    F.resize(owned_cells.size());
    cofactor.resize(owned_cells.size());
    J.resize(owned_cells.size());
    pbar.resize(owned_cells.size());
  }


  template <int dim>
  void
  NodalPressure<dim>::deformation(const VectorType &u)
  {
    const unsigned int n_e
      = nodal.cells.empty() ? 0 : nodal.cells[0].dofs.size();
    const auto &vector = u.trilinos_vector();
    if (ghost_length != vector.MyLength())
      {
        ghost_length = vector.MyLength();
        ghost_index.resize(owned_cells.size() * n_e);
        for (unsigned int o = 0; o < owned_cells.size(); ++o)
          for (unsigned int i = 0; i < n_e; ++i)
            {
              ghost_index[o * n_e + i] = vector.Map().LID(
                static_cast<TrilinosWrappers::types::int_type>(
                  nodal.cells[owned_cells[o]].dofs[i]));
              AssertThrow(ghost_index[o * n_e + i] >= 0, ExcInternalError());
            }
      }
    const double *values = vector[0];
    parallel::apply_to_subranges(
      0U,
      static_cast<unsigned int>(owned_cells.size()),
      [&](const unsigned int begin, const unsigned int end) {
        for (unsigned int o = begin; o < end; ++o)
          {
            const auto &cell = nodal.cells[owned_cells[o]];
            F[o]             = unit_symmetric_tensor<dim>();
            for (unsigned int i = 0; i < n_e; ++i)
              {
                const auto [node, component] = cell.node_component[i];
                F[o][component]
                  += values[ghost_index[o * n_e + i]] * cell.gradient[node];
              }
            J[o]        = determinant(F[o]);
            cofactor[o] = materials::cofactor(F[o]);
          }
      },
      256);
  }


  template <int dim>
  void
  NodalPressure<dim>::solve_pressures(
    const materials::MaterialSet<dim> &materials)
  {
    // b_i = int N_i g(J) = sum_e V_e g(J_e) / (d + 1) over the cells at i;
    // where the model is undefined (J <= 0) the cell adds nothing (it is
    // reported by assemble(), and its energy is infinite).
    std::vector<types::global_dof_index> where;
    std::vector<double>                  what;
    where.reserve(owned_cells.size() * (dim + 1));
    what.reserve(owned_cells.size() * (dim + 1));
    for (unsigned int o = 0; o < owned_cells.size(); ++o)
      {
        const auto &cell     = nodal.cells[owned_cells[o]];
        const auto &material = materials.material(cell.material_id);
        if (!(J[o] > 0) && !material.admits_inversion())
          continue;
        const double value
          = cell.volume * material.volumetric_part(J[o]).g / (dim + 1);
        for (unsigned int a = 0; a <= dim; ++a)
          {
            where.push_back(vertex[o][a]);
            what.push_back(value);
          }
      }
    b = 0;
    b.add(where, what);
    b.compress(VectorOperation::add);
    // The owned part of b (its ghosts only served the sum).
    std::memcpy(owned_b.trilinos_vector()[0],
                b.trilinos_vector()[0],
                owned_p.n_elements() * sizeof(double));
    factorization->solve(p, owned_b);
    pressure            = p;
    const double *local = pressure.trilinos_vector()[0];
    for (unsigned int o = 0; o < owned_cells.size(); ++o)
      {
        double sum = 0;
        for (unsigned int a = 0; a <= dim; ++a)
          sum += local[pressure_index[o * (dim + 1) + a]];
        pbar[o] = sum / (dim + 1);
      }
  }


  template <int dim>
  std::vector<double>
  NodalPressure<dim>::cell_pressures(
    const VectorType                  &u,
    const materials::MaterialSet<dim> &materials)
  {
    deformation(u);
    solve_pressures(materials);
    std::vector<double> result(n_active_cells, 0.);
    for (unsigned int o = 0; o < owned_cells.size(); ++o)
      result[nodal.cells[owned_cells[o]].active_index] = pbar[o];
    return result;
  }


  template <int dim>
  void
  NodalPressure<dim>::add_cell(const unsigned int               o,
                               const materials::Interface<dim> &material,
                               const Tensor<1, dim>            &fibre,
                               const materials::TangentMethod   method,
                               Vector<double>                  &r,
                               FullMatrix<double>              *K) const
  {
    const auto        &cell = nodal.cells[owned_cells[o]];
    const auto        &grad = cell.gradient;
    const unsigned int n_e  = cell.dofs.size();
    const unsigned int p0   = n_e;
    const double       V    = cell.volume;
    const auto         part = material.volumetric_part(J[o]);
    // The pressure beyond the model's own lambda g: the model's stress plus
    // (pbar - lambda g) dg/dF is the cell's.
    const double   s = pbar[o] - part.lambda * part.g;
    Tensor<2, dim> P;
    Tensor<4, dim> tangent;
    if (K)
      material.stress_and_tangent(F[o], fibre, P, tangent, method);
    else
      P = material.stress(F[o], fibre);
    // a_k = J F^{-T} grad N_k: dJ/du for (node k, component c) is a_k[c].
    std::array<Tensor<1, dim>, dim + 1> a;
    for (unsigned int k = 0; k <= dim; ++k)
      a[k] = cofactor[o] * grad[k];
    r.reinit(n_e + dim + 1);
    for (unsigned int i = 0; i < n_e; ++i)
      {
        const auto [k, c] = cell.node_component[i];
        r(i)              = V * (P[c] * grad[k] + s * part.dg * a[k][c]);
      }
    if (!K)
      return;
    K->reinit(n_e + dim + 1, n_e + dim + 1);
    const double h = part.d2g * s - part.lambda * part.dg * part.dg;
    for (unsigned int i = 0; i < n_e; ++i)
      {
        const auto [k, c] = cell.node_component[i];
        for (unsigned int j = 0; j < n_e; ++j)
          {
            const auto [l, d] = cell.node_component[j];
            double value      = 0;
            for (unsigned int m = 0; m < dim; ++m)
              for (unsigned int n = 0; n < dim; ++n)
                value += tangent[c][m][d][n] * grad[k][m] * grad[l][n];
            // (s g'' - lambda g'^2) dJ dJ + s g' d2J, d2J from the
            // cofactor's derivative (nodal_dilatation.cc).
            value += h * a[k][c] * a[l][d];
            if (J[o] != 0)
              value
                += s * part.dg / J[o] * (a[k][c] * a[l][d] - a[l][c] * a[k][d]);
            (*K)(i, j) = V * value;
          }
        // B = db/du: the vertices' share of V g' dJ.
        const double entry = V / (dim + 1) * part.dg * a[k][c];
        for (unsigned int v = 0; v <= dim; ++v)
          {
            (*K)(p0 + v, i) = entry;
            (*K)(i, p0 + v) = entry;
          }
      }
    for (unsigned int v = 0; v <= dim; ++v)
      for (unsigned int w = 0; w <= dim; ++w)
        (*K)(p0 + v, p0 + w) = -pressure_entry<dim>(
          V, v == w, moduli[o][0], moduli[o][1], stabilization);
  }


  template <int dim>
  std::vector<std::tuple<unsigned int, double, Point<dim>>>
  NodalPressure<dim>::assemble(const VectorType                  &u,
                               const materials::MaterialSet<dim> &materials,
                               const FibreField<dim>             &fibres,
                               const AffineConstraints<double>   &rows,
                               const bool                         inhomogeneous,
                               const bool                         jacobian,
                               VectorType                        &residual)
  {
    AssertThrow(!jacobian || system_built, ExcInternalError());
    deformation(u);
    solve_pressures(materials);
    if (jacobian)
      copy_dirichlet_lines(rows, relevant, augmented_rows);

    std::vector<std::tuple<unsigned int, double, Point<dim>>> inverted;
    const unsigned int n_o = owned_cells.size();
    // Cells computed in parallel by chunks, added in order (the sums do
    // not depend on the threads).
    const unsigned int chunk = 2048;
    // The cells' rows and blocks, kept from call to call (the line search
    // asks for many residuals).
    auto &r         = cell_rows;
    auto &K         = cell_blocks;
    auto &undefined = cell_undefined;
    r.resize(std::max<std::size_t>(r.size(), std::min(n_o, chunk)));
    undefined.resize(r.size());
    if (jacobian)
      K.resize(r.size());
    for (unsigned int first = 0; first < n_o; first += chunk)
      {
        const unsigned int last = std::min(n_o, first + chunk);
        parallel::apply_to_subranges(
          first,
          last,
          [&](const unsigned int begin, const unsigned int end) {
            for (unsigned int o = begin; o < end; ++o)
              {
                const auto &cell     = nodal.cells[owned_cells[o]];
                const auto &material = materials.material(cell.material_id);
                undefined[o - first]
                  = !(J[o] > 0) && !material.admits_inversion();
                if (!undefined[o - first])
                  add_cell(o,
                           material,
                           fibres.at(cell.active_index, 0),
                           materials.tangent_method(),
                           r[o - first],
                           jacobian ? &K[o - first] : nullptr);
              }
          },
          32);
        for (unsigned int o = first; o < last; ++o)
          if (undefined[o - first])
            {
              const auto &cell = nodal.cells[owned_cells[o]];
              inverted.emplace_back(cell.active_index, J[o], cell.centre);
            }
          else
            add_rows(o,
                     r[o - first],
                     jacobian ? &K[o - first] : nullptr,
                     rows,
                     inhomogeneous,
                     residual);
      }
    return inverted;
  }


  template <int dim>
  void
  NodalPressure<dim>::add_rows(const unsigned int               o,
                               const Vector<double>            &r,
                               const FullMatrix<double>        *K,
                               const AffineConstraints<double> &rows,
                               const bool                       inhomogeneous,
                               VectorType                      &residual)
  {
    const auto        &dofs = nodal.cells[owned_cells[o]].dofs;
    const unsigned int n_e  = dofs.size();
    const unsigned int n_a  = n_e + dim + 1;
    if (K && direct_row[std::size_t(o) * n_a] >= 0)
      {
        // In place: owned, free rows.
        const int *row        = &direct_row[std::size_t(o) * n_a];
        double    *rhs_values = rhs.trilinos_vector()[0];
        for (unsigned int i = 0; i < n_a; ++i)
          {
            rhs_values[row[i]] += r(i);
            double              *values = row_values[row[i]];
            const std::uint16_t *entry
              = &direct_entry[(std::size_t(o) * n_a + i) * n_a];
            for (unsigned int j = 0; j < n_a; ++j)
              values[entry[j]] += (*K)(i, j);
          }
      }
    else if (K)
      {
        std::vector<types::global_dof_index> indices(dofs.begin(), dofs.end());
        for (unsigned int v = 0; v <= dim; ++v)
          indices.push_back(n_u + vertex[o][v]);
        augmented_rows.distribute_local_to_global(
          *K, r, indices, matrix, rhs, inhomogeneous);
      }
    else if (residual_row[std::size_t(o) * n_e] >= 0)
      {
        // In place: owned, free rows.
        const int *row    = &residual_row[std::size_t(o) * n_e];
        double    *values = residual.trilinos_vector()[0];
        for (unsigned int i = 0; i < n_e; ++i)
          values[row[i]] += r(i);
      }
    else
      {
        Vector<double>                       r_u(r.begin(), r.begin() + n_e);
        std::vector<types::global_dof_index> indices(dofs.begin(), dofs.end());
        rows.distribute_local_to_global(r_u, indices, residual);
      }
  }


  template <int dim>
  void
  NodalPressure<dim>::build_system(const AffineConstraints<double> *constraints)
  {
    system_built = false;
    if (!constraints)
      return;
    const MPI_Comm comm = parallel_tools::communicator();
    copy_dirichlet_lines(*constraints, relevant, augmented_rows);
    TrilinosWrappers::SparsityPattern    sparsity(owned, owned, relevant, comm);
    std::vector<types::global_dof_index> indices;
    for (unsigned int o = 0; o < owned_cells.size(); ++o)
      {
        const auto &dofs = nodal.cells[owned_cells[o]].dofs;
        indices.assign(dofs.begin(), dofs.end());
        for (unsigned int v = 0; v <= dim; ++v)
          indices.push_back(n_u + vertex[o][v]);
        augmented_rows.add_entries_local_to_global(indices, sparsity, false);
      }
    sparsity.compress();
    matrix.reinit(sparsity);
    rhs.reinit(owned, relevant, comm, true);
    uu_row.clear();
    uu_entry.clear();
    build_direct_access(*constraints);
    system_built = true;
  }


  template <int dim>
  void
  NodalPressure<dim>::build_direct_access(
    const AffineConstraints<double> &constraints)
  {
    const unsigned int n_a
      = nodal.cells.empty() ? 0 : nodal.cells[0].dofs.size() + dim + 1;
    row_values = row_value_pointers(matrix);
    direct_row.assign(owned_cells.size() * n_a, -1);
    direct_entry.assign(owned_cells.size() * n_a * n_a, 0);
    std::vector<types::global_dof_index> indices;
    for (unsigned int o = 0; o < owned_cells.size(); ++o)
      {
        const auto &dofs = nodal.cells[owned_cells[o]].dofs;
        bool        free = true;
        for (const auto i : dofs)
          free = free && owned.is_element(i) && !constraints.is_constrained(i);
        if (!free)
          continue;
        indices.assign(dofs.begin(), dofs.end());
        for (unsigned int v = 0; v <= dim; ++v)
          indices.push_back(n_u + vertex[o][v]);
        for (unsigned int i = 0; i < n_a; ++i)
          {
            const int r = owned.index_within_set(indices[i]);
            direct_row[std::size_t(o) * n_a + i] = r;
            for (unsigned int j = 0; j < n_a; ++j)
              {
                const int position = entry_in_row(matrix, r, indices[j]);
                AssertThrow(position < 65536, ExcInternalError());
                direct_entry[(std::size_t(o) * n_a + i) * n_a + j] = position;
              }
          }
      }
  }


  template <int dim>
  void
  NodalPressure<dim>::clear()
  {
    if (!system_built)
      return;
    matrix = 0;
    rhs    = 0;
  }


  template <int dim>
  void
  NodalPressure<dim>::finish(const MatrixType *uu, VectorType &residual)
  {
    finish_augmented(matrix, rhs, uu, uu_row, uu_entry, residual);
  }


  template <int dim>
  void
  NodalPressure<dim>::solve(solvers::LinearSolver &solver,
                            VectorType            &x,
                            const VectorType      &rhs_u,
                            const bool             refactorize)
  {
    solve_augmented(solver, matrix, rhs, owned, x, rhs_u, refactorize);
  }


  template <int dim>
  std::size_t
  NodalPressure<dim>::memory_consumption() const
  {
    return A.memory_consumption() + matrix.memory_consumption()
           + (F.size() + cofactor.size()) * sizeof(Tensor<2, dim>)
           + (J.size() + pbar.size()) * sizeof(double)
           + vertex.size() * sizeof(vertex[0]);
  }


  template class NodalPressure<1>;
  template class NodalPressure<2>;
  template class NodalPressure<3>;
} // namespace tissuefem::solid
