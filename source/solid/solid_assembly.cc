// Assembly of the general (quadrature-loop) path: residuals, Jacobians
// and forces of any element and formulation, cell by cell in parallel
// (deal.II's WorkStream); the lean P1 kernel is in solid_lean.cc.
#include <deal.II/base/work_stream.h>
#include <deal.II/fe/fe_values.h>

#include <tissuefem/solid/solid.h>

#include <Epetra_FEVector.h>

#include <algorithm>
#include <sstream>

#include <chrono>

namespace tissuefem::solid
{
  namespace
  {
    /// Per-thread work space of an assembly pass: the formulation's cell
    /// terms, the inertia coefficients, loads.
    template <int dim>
    struct Scratch
    {
      Scratch(const Discretization<dim>          &discretization,
              const formulations::Interface<dim> &formulation,
              const formulations::Context<dim>   &context,
              const bool                          faces)
          : cell(context.cache.n_scalar, context.cache.n_q)
          , W(context.cache.n_scalar)
          , body_force(dim)
          , traction(dim)
      {
        cell.own = formulation.make_scratch(context);
        if (faces)
          face_values = std::make_unique<FEFaceValues<dim>>(
            *discretization.mapping,
            *discretization.fe,
            discretization.face_quadrature,
            update_values | update_quadrature_points | update_JxW_values);
      }

      Scratch(const Scratch &other)
          : cell(other.cell)
          , W(other.W)
          , body_force(dim)
          , traction(dim)
      {
        if (other.face_values)
          face_values = std::make_unique<FEFaceValues<dim>>(
            other.face_values->get_mapping(),
            other.face_values->get_fe(),
            other.face_values->get_quadrature(),
            other.face_values->get_update_flags());
      }

      formulations::CellTerms<dim>       cell;
      std::vector<Tensor<1, dim>>        W;
      Vector<double>                     body_force, traction;
      std::unique_ptr<FEFaceValues<dim>> face_values;
    };

    /// What one cell adds to the global objects.
    struct Copy
    {
      explicit Copy(const unsigned int n)
          : matrix(n, n)
          , rhs(n)
          , dofs(n)
      {
      }
      FullMatrix<double>                   matrix;
      Vector<double>                       rhs;
      std::vector<types::global_dof_index> dofs;
      /// Smallest det F of the cell where the model cannot represent
      /// inversion (1 if none is inverted).
      double       inverted_det = 1;
      unsigned int cell_index   = 0;
      unsigned int cache_index  = 0;
    };
  } // namespace


  template <int dim>
  template <typename ScratchType, typename CopyType>
  void
  Solid<dim>::start_cell(const Request     &request,
                         const unsigned int c,
                         ScratchType       &s,
                         CopyType          &copy) const
  {
    const unsigned int n    = cache.n_dofs;
    const auto        *dofs = cache.dofs(c);
    std::copy(dofs, dofs + n, copy.dofs.begin());
    copy.cell_index   = cache.cells()[c]->active_cell_index();
    copy.cache_index  = c;
    copy.inverted_det = 1;
    copy.rhs          = 0;
    if (request.jacobian)
      copy.matrix = 0;
    auto &cell        = s.cell;
    cell.c            = c;
    cell.index        = copy.cell_index;
    cell.material     = &materials.material(cache.cells()[c]->material_id());
    cell.jacobian     = request.jacobian;
    cell.carry_time   = request.carry ? &request.time : nullptr;
    cell.rhs          = &copy.rhs;
    cell.matrix       = &copy.matrix;
    cell.inverted_det = 1;
    // Raw local data of the ghosted arguments (see DirectAccess).
    const double *u_values
      = request.internal ? request.u->trilinos_vector()[0] : nullptr;
    const double *w_values
      = request.inertia ? request.inertia->trilinos_vector()[0] : nullptr;
    for (unsigned int k = 0; k < cache.n_scalar; ++k)
      for (unsigned int a = 0; a < dim; ++a)
        {
          const unsigned int i = cache.local_index[k * dim + a];
          const int          g = access.ghost_index[c * n + i];
          cell.U[k][a]         = u_values ? u_values[g] : 0.;
          s.W[k][a]            = w_values ? w_values[g] : 0.;
        }
  }


  template <int dim>
  template <typename ScratchType, typename CopyType>
  void
  Solid<dim>::add_point_terms(const Request     &request,
                              const unsigned int c,
                              const double       rho,
                              const bool         elastic,
                              ScratchType       &s,
                              CopyType          &copy) const
  {
    const unsigned int n_scalar      = cache.n_scalar;
    const double      *JxW           = cache.JxW(c);
    const double       mass_jacobian = request.mass_jacobian_coefficient * rho;
    // The lumped mass's row k is int rho N_k (the shape functions sum to
    // one): inertia rho N_k w_k and Jacobian c rho N_k at the points.
    const bool     lumped = discretization.lumped_mass;
    Tensor<3, dim> B;
    for (unsigned int q = 0; q < cache.n_q; ++q)
      {
        const Tensor<2, dim> &P = s.cell.P[q];
        const Tensor<4, dim> &A = s.cell.A[q];
        // Loads per unit reference volume, with the inertial term rho w
        // acting like a load.
        Tensor<1, dim> load;
        if (request.external)
          {
            load = rho * boundary_conditions.gravity;
            if (body_force_present)
              {
                boundary_conditions.body_force->vector_value(cache.point(c, q),
                                                             s.body_force);
                for (unsigned int d = 0; d < dim; ++d)
                  load[d] += s.body_force[d];
              }
            load *= boundary_conditions.load_factor;
          }
        if (request.inertia && !lumped)
          for (unsigned int k = 0; k < n_scalar; ++k)
            load -= (rho * cache.values[q * n_scalar + k]) * s.W[k];

        for (unsigned int k = 0; k < n_scalar; ++k)
          {
            const Tensor<1, dim> &g_k   = cache.gradient(c, q, k);
            const double          phi_k = cache.values[q * n_scalar + k];
            Tensor<1, dim>        r     = -phi_k * load;
            if (request.inertia && lumped)
              r += (rho * phi_k) * s.W[k];
            if (elastic)
              r += P * g_k;
            for (unsigned int a = 0; a < dim; ++a)
              copy.rhs[cache.local_index[k * dim + a]] += r[a] * JxW[q];
            if (!request.jacobian)
              continue;
            // B_k[a][b][e] = A[a][m][b][e] g_k[m], so that
            // K_(k a)(l b) = B_k[a][b] . g_l (problem session eq 19).
            if (elastic)
              for (unsigned int a = 0; a < dim; ++a)
                {
                  B[a] = 0;
                  for (unsigned int m = 0; m < dim; ++m)
                    B[a] += g_k[m] * A[a][m];
                }
            for (unsigned int a = 0; a < dim; ++a)
              {
                const unsigned int i = cache.local_index[k * dim + a];
                for (unsigned int l = 0; l < n_scalar; ++l)
                  {
                    const Tensor<1, dim> &g_l = cache.gradient(c, q, l);
                    const double          mass_kl
                      = lumped ? (k == l ? mass_jacobian * phi_k : 0.)
                               : mass_jacobian * phi_k
                                   * cache.values[q * n_scalar + l];
                    for (unsigned int b = 0; b < dim; ++b)
                      {
                        const unsigned int j = cache.local_index[l * dim + b];
                        if (j < i)
                          continue;
                        double value = elastic ? B[a][b] * g_l : 0.;
                        if (a == b)
                          value += mass_kl;
                        copy.matrix(i, j) += value * JxW[q];
                      }
                  }
              }
          }
      }
  }


  template <int dim>
  template <typename ScratchType, typename CopyType>
  void
  Solid<dim>::add_tractions(const unsigned int c,
                            ScratchType       &s,
                            CopyType          &copy) const
  {
    const auto &cell = cache.cells()[c];
    const auto &fe   = *discretization.fe;
    for (const auto &face : cell->face_iterators())
      if (face->at_boundary())
        for (const auto &condition : boundary_conditions.neumann)
          if (face->boundary_id() == condition.id)
            {
              auto &fv = *s.face_values;
              fv.reinit(cell, face);
              for (const unsigned int q : fv.quadrature_point_indices())
                {
                  condition.traction->vector_value(fv.quadrature_point(q),
                                                   s.traction);
                  const double scale
                    = boundary_conditions.load_factor * fv.JxW(q);
                  for (unsigned int i = 0; i < cache.n_dofs; ++i)
                    copy.rhs[i]
                      -= s.traction[fe.system_to_component_index(i).first]
                         * fv.shape_value(i, q) * scale;
                }
            }
  }


  template <int dim>
  template <typename CopyType>
  void
  Solid<dim>::add_to_global(const Request  &request,
                            const CopyType &copy,
                            VectorType     &residual)
  {
    const unsigned int n = cache.n_dofs;
    const unsigned int c = copy.cache_index;
    if (access.direct[c])
      {
        // Owned dofs under no constraint: every row set used here (the
        // constraints, their lifted variant, none) treats them alike, so
        // add in place.
        double    *residual_values = residual.trilinos_vector()[0];
        const int *row             = &access.row[c * n];
        for (unsigned int i = 0; i < n; ++i)
          residual_values[row[i]] += copy.rhs[i];
        if (request.jacobian)
          for (unsigned int i = 0; i < n; ++i)
            {
              double              *values = access.row_values[row[i]];
              const std::uint16_t *entry  = &access.entry[(c * n + i) * n];
              for (unsigned int j = 0; j < n; ++j)
                values[entry[j]] += copy.matrix(i, j);
            }
        return;
      }
    if (request.jacobian)
      request.rows->distribute_local_to_global(copy.matrix,
                                               copy.rhs,
                                               copy.dofs,
                                               jacobian_matrix,
                                               residual,
                                               request.inhomogeneous);
    else
      request.rows->distribute_local_to_global(copy.rhs, copy.dofs, residual);
  }


  template <int dim>
  void
  Solid<dim>::assemble(const Request &request, VectorType &residual)
  {
    if (request.jacobian)
      prepare_jacobian();
    if (uses_lean_kernel(request))
      {
        assemble_lean(request, residual);
        return;
      }
    const bool neumann
      = request.external && !boundary_conditions.neumann.empty();
    boundary_conditions.set_time(request.time);
    discretization.initialize_assembly_vector(residual);
    if (request.jacobian)
      jacobian_matrix = 0;

    // One cell: its elastic part (the formulation's stresses at the
    // points, or its own rows), loads and inertia at the points, tractions
    // on its boundary faces. A cell whose state the formulation or model
    // cannot represent (an inverted point) contributes nothing; it is
    // reported. Terms that couple patches of cells follow the loop.
    const formulations::Context<dim> context = this->context();
    auto worker = [&](const std::vector<unsigned int>::const_iterator &it,
                      Scratch<dim>                                    &s,
                      Copy                                            &copy) {
      const unsigned int c = *it;
      start_cell(request, c, s, copy);
      const auto &cell = cache.cells()[c];
      const bool  elastic
        = request.internal && element->cell_terms(context, s.cell);
      copy.inverted_det = s.cell.inverted_det;
      if (copy.inverted_det <= 0)
        return;
      add_point_terms(
        request, c, materials.density(cell->material_id()), elastic, s, copy);
      if (request.internal)
        element->add_cell_rows(context, s.cell);
      if (neumann && cell->at_boundary())
        add_tractions(c, s, copy);
      if (request.jacobian)
        for (unsigned int i = 0; i < cache.n_dofs; ++i)
          for (unsigned int j = 0; j < i; ++j)
            copy.matrix(i, j) = copy.matrix(j, i);
    };

    std::vector<std::tuple<unsigned int, double, Point<dim>>> inverted;
    auto copier = [&](const Copy &copy) {
      if (copy.inverted_det <= 0)
        inverted.emplace_back(copy.cell_index,
                              copy.inverted_det,
                              cache.cells()[copy.cache_index]->center());
      else
        add_to_global(request, copy, residual);
    };

    std::vector<unsigned int> indices;
    indices.reserve(cache.cells().size());
    for (unsigned int c = 0; c < cache.cells().size(); ++c)
      if (!request.cells || (*request.cells)[c])
        indices.push_back(c);
    WorkStream::run(indices.cbegin(),
                    indices.cend(),
                    worker,
                    copier,
                    Scratch<dim>(discretization, *element, context, neumann),
                    Copy(cache.n_dofs));
    add_patch_terms(request, residual, inverted);
    add_contributions(request, residual);

    residual.compress(VectorOperation::add);
    if (request.jacobian)
      jacobian_matrix.compress(VectorOperation::add);
    if (request.jacobian)
      element->finish_system(&jacobian_matrix, residual);
    if (request.internal)
      element->assembled();
    report_inversions(inverted);
  }


  template <int dim>
  void
  Solid<dim>::prepare_jacobian()
  {
    if (element->couples_patches() && !element->has_system() && !wide_layout)
      build_jacobian_matrix(true);
    element->clear_system();
  }


  template <int dim>
  void
  Solid<dim>::add_patch_terms(const Request               &request,
                              VectorType                  &residual,
                              formulations::Inverted<dim> &inverted,
                              const bool                   loads)
  {
    if (!element->couples_patches() || !request.internal)
      return;
    formulations::PatchRequest<dim> patch;
    patch.u             = request.u;
    patch.jacobian      = request.jacobian;
    patch.rows          = request.rows;
    patch.inhomogeneous = request.inhomogeneous;
    patch.loads         = loads;
    if (loads)
      {
        patch.inertia          = request.inertia;
        patch.mass_coefficient = request.mass_jacobian_coefficient;
        patch.lumped_mass      = discretization.lumped_mass;
        if (request.external)
          patch.gravity
            = boundary_conditions.load_factor * boundary_conditions.gravity;
      }
    element->add_patch_terms(
      context(), patch, jacobian_matrix, residual, inverted);
  }


  template <int dim>
  void
  Solid<dim>::add_contributions(const Request &request, VectorType &residual)
  {
    if (!request.internal || !request.contributions || contributions.empty())
      return;
    const auto start = std::chrono::steady_clock::now();
    for (const auto &contribution : contributions)
      contribution->add(*request.u,
                        request.time,
                        request.jacobian,
                        *request.rows,
                        request.inhomogeneous,
                        jacobian_matrix,
                        residual);
    contribution_time
      += std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
           .count();
  }


  template <int dim>
  void
  Solid<dim>::report_inversions(
    const std::vector<std::tuple<unsigned int, double, Point<dim>>> &inverted)
    const
  {
    // Every process must learn of an inversion anywhere: gather (active
    // cell index, det F, centre) of the inverted cells.
    std::vector<double> flat;
    for (const auto &[index, det, center] : inverted)
      {
        flat.push_back(index);
        flat.push_back(det);
        for (unsigned int d = 0; d < dim; ++d)
          flat.push_back(center[d]);
      }
    std::vector<std::vector<double>> everywhere
      = Utilities::MPI::all_gather(parallel_tools::communicator(), flat);
    std::vector<std::vector<double>> cells;
    for (const auto &part : everywhere)
      for (unsigned int i = 0; i < part.size(); i += dim + 2)
        cells.emplace_back(part.begin() + i, part.begin() + i + dim + 2);
    if (cells.empty())
      return;
    std::sort(cells.begin(), cells.end());
    double smallest = 0;
    for (const auto &cell : cells)
      smallest = std::min(smallest, cell[1]);
    std::ostringstream message;
    message << cells.size()
            << " element(s) inverted (smallest det F = " << smallest
            << "): cell";
    for (unsigned int i = 0; i < std::min<std::size_t>(cells.size(), 4); ++i)
      {
        message << (i ? ", " : " ") << static_cast<unsigned int>(cells[i][0])
                << " at (";
        for (unsigned int d = 0; d < dim; ++d)
          message << (d ? " " : "") << cells[i][2 + d];
        message << ")";
      }
    if (cells.size() > 4)
      message << ", ...";
    message << "; " << element->inversion_advice();
    throw InvertedElementError(message.str());
  }


#define TISSUEFEM_INSTANTIATE(dim)                                            \
  template void Solid<dim>::assemble(const Request &, VectorType &);          \
  template void Solid<dim>::add_contributions(const Request &, VectorType &); \
  template void Solid<dim>::add_patch_terms(const Request &,                  \
                                            VectorType &,                     \
                                            formulations::Inverted<dim> &,    \
                                            const bool);                      \
  template void Solid<dim>::report_inversions(                                \
    const std::vector<std::tuple<unsigned int, double, Point<dim>>> &) const;

  TISSUEFEM_INSTANTIATE(1)
  TISSUEFEM_INSTANTIATE(2)
  TISSUEFEM_INSTANTIATE(3)
#undef TISSUEFEM_INSTANTIATE
} // namespace tissuefem::solid
