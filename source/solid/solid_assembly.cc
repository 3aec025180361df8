// Assembly of the general (quadrature-loop) path: residuals, Jacobians
// and forces of any element and formulation, cell by cell in parallel
// (deal.II's WorkStream); the lean P1 kernel is in solid_lean.cc.
#include <deal.II/base/work_stream.h>
#include <deal.II/fe/fe_values.h>

#include <tissuefem/materials/kinematics.h>
#include <tissuefem/materials/tangent_projection.h>
#include <tissuefem/solid/edge_length_element.h>
#include <tissuefem/solid/mean_dilatation.h>
#include <tissuefem/solid/solid.h>

#include <Epetra_FEVector.h>

#include <algorithm>
#include <sstream>

#include <chrono>

namespace tissuefem::solid
{
  namespace
  {
    /// Per-thread work space of an assembly pass.
    template <int dim>
    struct Scratch
    {
      Scratch(const Discretization<dim> &discretization, const bool faces)
          : U(discretization.fe->base_element(0).n_dofs_per_cell())
          , W(U.size())
          , vertices(U.size())
          , gradients(U.size())
          , body_force(dim)
          , traction(dim)
      {
        resize(discretization.cell_quadrature.size());
        if (faces)
          face_values = std::make_unique<FEFaceValues<dim>>(
            *discretization.mapping,
            *discretization.fe,
            discretization.face_quadrature,
            update_values | update_quadrature_points | update_JxW_values);
      }

      Scratch(const Scratch &other)
          : U(other.U)
          , W(other.W)
          , vertices(other.vertices)
          , gradients(other.gradients)
          , body_force(dim)
          , traction(dim)
      {
        resize(other.F.size());
        if (other.face_values)
          face_values = std::make_unique<FEFaceValues<dim>>(
            other.face_values->get_mapping(),
            other.face_values->get_fe(),
            other.face_values->get_quadrature(),
            other.face_values->get_update_flags());
      }

      void
      resize(const unsigned int n_q)
      {
        F.resize(n_q);
        P.resize(n_q);
        A.resize(n_q);
        b.resize(U.size());
        C.resize(U.size());
      }

      std::vector<Tensor<1, dim>> U, W;
      /// Mean dilatation: per-point deformation gradients, effective
      /// stresses and tangents, and per shape function dtheta/du (b) and
      /// sum_q w_q phi_Ftheta g (C); see mean_dilatation.h.
      std::vector<Tensor<2, dim>>        F, P;
      std::vector<Tensor<4, dim>>        A;
      std::vector<Tensor<1, dim>>        b, C;
      double                             Theta = 0;
      std::vector<Point<dim>>            vertices;
      std::vector<Tensor<1, dim>>        gradients;
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
  template <typename ScratchType>
  std::pair<double, double>
  Solid<dim>::dilatation_point_terms(const materials::Interface<dim> &material,
                                     const unsigned int               c,
                                     const unsigned int cell_index,
                                     const double       theta,
                                     const bool         linearize,
                                     ScratchType       &s) const
  {
    const unsigned int n_q = cache.n_q, n_scalar = cache.n_scalar;
    const double      *JxW    = cache.JxW(c);
    const auto         method = materials.tangent_method();
    double             volume = 0, Phi_theta = 0;
    s.Theta = 0;
    for (unsigned int k = 0; k < n_scalar; ++k)
      s.b[k] = s.C[k] = Tensor<1, dim>();
    MeanDilatationPoint<dim> point;
    Tensor<2, dim>           P_bar;
    Tensor<4, dim>           A_bar;
    for (unsigned int q = 0; q < n_q; ++q)
      {
        const Tensor<2, dim> F_bar
          = modified_deformation_gradient(s.F[q], theta);
        const Tensor<1, dim> &a = fibre_field.at(cell_index, q);
        if (linearize)
          {
            material.stress_and_tangent(F_bar, a, P_bar, A_bar, method);
            if (materials.project_tangent())
              materials::project_to_positive_definite(A_bar);
            mean_dilatation_stress_and_tangent(
              s.F[q], theta, P_bar, A_bar, point);
            s.A[q] = point.phi_FF;
            s.Theta += JxW[q] * point.phi_theta_theta;
            const Tensor<2, dim> cof = cofactor(s.F[q]);
            for (unsigned int k = 0; k < n_scalar; ++k)
              {
                const Tensor<1, dim> &g = cache.gradient(c, q, k);
                s.C[k] += JxW[q] * (point.phi_F_theta * g);
                s.b[k] += JxW[q] * (cof * g);
              }
          }
        else
          mean_dilatation_stress(s.F[q],
                                 theta,
                                 material.stress(F_bar, a),
                                 point);
        s.P[q] = point.phi_F;
        Phi_theta += JxW[q] * point.phi_theta;
        volume += JxW[q];
      }
    for (unsigned int k = 0; k < n_scalar; ++k)
      s.b[k] /= volume;
    return {volume, Phi_theta};
  }


  template <int dim>
  template <typename ScratchType, typename CopyType>
  void
  Solid<dim>::mean_dilatation_cell(const materials::Interface<dim> &material,
                                   const unsigned int               c,
                                   const unsigned int               cell_index,
                                   const bool                       jacobian,
                                   const double                     carried,
                                   ScratchType                     &s,
                                   CopyType                        &copy) const
  {
    const double mean = solid::mean_dilatation(s.F, cache.JxW(c), cache.n_q);
    if (mean <= 0)
      {
        copy.inverted_det = mean;
        return;
      }
    // A carried dilatation scales theta by a constant: dtheta/du (b) and
    // the pressure-like term scale with it, Theta and C do not.
    const auto [volume, Phi_theta] = dilatation_point_terms(
      material, c, cell_index, carried * mean, jacobian, s);
    for (unsigned int k = 0; k < cache.n_scalar; ++k)
      s.b[k] *= carried;
    // The pressure-like term Phi_theta/V couples every point through
    // theta: its first derivative is cof F_q, its second dcof/dF.
    add_cell_pressure(carried * Phi_theta / volume, jacobian, s);
  }


  template <int dim>
  template <typename ScratchType, typename CopyType>
  void
  Solid<dim>::three_field_cell(const materials::Interface<dim> &material,
                               const unsigned int               c,
                               const unsigned int               cell_index,
                               const bool                       jacobian,
                               ScratchType                     &s,
                               CopyType                        &copy) const
  {
    const double mean = solid::mean_dilatation(s.F, cache.JxW(c), cache.n_q);
    // The first assembly of a step sets the unknowns: the carried
    // dilatation of a changed cell (the old mesh's, so that its pressure
    // is the old one and the momentum rows start balanced), else the
    // cell's own; the pressure consistent with it.
    if (three_field.initializing() && mean > 0)
      three_field.theta(c) = mean * carry.factor(cell_index, three_field_start);
    const double theta = three_field.theta(c);
    if (mean <= 0 || theta <= 0)
      {
        copy.inverted_det = std::min(mean, theta);
        return;
      }
    // The cell's b, C and Theta are those of the last Jacobian, so that
    // modified Newton ('Jacobian reuse') condenses with the matrix it
    // solves with.
    const bool linearize = jacobian || !three_field.linearized(c);
    const auto [volume, Phi_theta]
      = dilatation_point_terms(material, c, cell_index, theta, linearize, s);
    if (three_field.initializing())
      three_field.pressure(c) = Phi_theta / volume;
    const double pressure = three_field.pressure(c);
    add_cell_pressure(pressure, jacobian, s);
    if (linearize)
      {
        std::vector<double> b(cache.n_dofs), C(cache.n_dofs);
        for (unsigned int k = 0; k < cache.n_scalar; ++k)
          for (unsigned int a = 0; a < dim; ++a)
            {
              b[cache.local_index[k * dim + a]] = s.b[k][a];
              C[cache.local_index[k * dim + a]] = s.C[k][a];
            }
        three_field.set_linearization(
          c, std::move(b), std::move(C), s.Theta, volume);
      }
    three_field.add_condensed_rows(c,
                                   mean - theta,
                                   Phi_theta - pressure * volume,
                                   copy.rhs);
  }


  template <int dim>
  template <typename ScratchType>
  void
  Solid<dim>::add_cell_pressure(const double pressure,
                                const bool   jacobian,
                                ScratchType &s) const
  {
    for (unsigned int q = 0; q < cache.n_q; ++q)
      {
        s.P[q] += pressure * cofactor(s.F[q]);
        if (jacobian)
          materials::add_cofactor_derivative(s.F[q], pressure, s.A[q]);
      }
  }


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
          s.U[k][a]            = u_values ? u_values[g] : 0.;
          s.W[k][a]            = w_values ? w_values[g] : 0.;
        }
  }


  template <int dim>
  template <typename ScratchType, typename CopyType>
  void
  Solid<dim>::cell_deformation(const Request                   &request,
                               const materials::Interface<dim> &material,
                               const unsigned int               c,
                               ScratchType                     &s,
                               CopyType                        &copy) const
  {
    // F at every point first. In the displacement formulation an inverted
    // point (where the model cannot represent it) discards the whole
    // cell, and the report gives the cell's smallest det F; the mean
    // dilatation element checks its points itself.
    const bool mean_dilatation = materials.mean_dilatation_formulation();
    for (unsigned int q = 0; q < cache.n_q; ++q)
      {
        Tensor<2, dim> &F = s.F[q];
        F                 = unit_symmetric_tensor<dim>();
        for (unsigned int k = 0; k < cache.n_scalar; ++k)
          F += outer_product(s.U[k], cache.gradient(c, q, k));
        if (mean_dilatation)
          continue;
        const double det = determinant(F);
        if (det <= 0 && !material.admits_inversion())
          copy.inverted_det = std::min(copy.inverted_det, det);
      }
    if (!mean_dilatation)
      return;
    if (three_field.active())
      three_field_cell(material, c, copy.cell_index, request.jacobian, s, copy);
    else
      mean_dilatation_cell(material,
                           c,
                           copy.cell_index,
                           request.jacobian,
                           request.carry
                             ? carry.factor(copy.cell_index, request.time)
                             : 1.,
                           s,
                           copy);
  }


  template <int dim>
  template <typename ScratchType, typename CopyType, typename StressAt>
  void
  Solid<dim>::add_point_terms_with(const Request     &request,
                                   const unsigned int c,
                                   const double       rho,
                                   const bool         elastic,
                                   const StressAt    &stress_at,
                                   ScratchType       &s,
                                   CopyType          &copy) const
  {
    const unsigned int n_scalar      = cache.n_scalar;
    const double      *JxW           = cache.JxW(c);
    const double       mass_jacobian = request.mass_jacobian_coefficient * rho;
    Tensor<2, dim>     P;
    Tensor<4, dim>     A;
    Tensor<3, dim>     B;
    for (unsigned int q = 0; q < cache.n_q; ++q)
      {
        if (elastic)
          stress_at(q, P, A);
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
        if (request.inertia)
          for (unsigned int k = 0; k < n_scalar; ++k)
            load -= (rho * cache.values[q * n_scalar + k]) * s.W[k];

        for (unsigned int k = 0; k < n_scalar; ++k)
          {
            const Tensor<1, dim> &g_k   = cache.gradient(c, q, k);
            const double          phi_k = cache.values[q * n_scalar + k];
            Tensor<1, dim>        r     = -phi_k * load;
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
                      = mass_jacobian * phi_k * cache.values[q * n_scalar + l];
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
  Solid<dim>::add_point_terms(const Request                   &request,
                              const materials::Interface<dim> &material,
                              const unsigned int               c,
                              const double                     rho,
                              const bool                       elastic,
                              ScratchType                     &s,
                              CopyType                        &copy) const
  {
    const auto method  = materials.tangent_method();
    const bool project = materials.project_tangent();
    // The formulation's stress (and tangent) at point q: the mean
    // dilatation's were computed for the whole cell, the displacement
    // formulation's come from F at the point.
    if (materials.mean_dilatation_formulation())
      add_point_terms_with(
        request,
        c,
        rho,
        elastic,
        [&](const unsigned int q, Tensor<2, dim> &P, Tensor<4, dim> &A) {
          P = s.P[q];
          if (request.jacobian)
            A = s.A[q];
        },
        s,
        copy);
    else
      add_point_terms_with(
        request,
        c,
        rho,
        elastic,
        [&](const unsigned int q, Tensor<2, dim> &P, Tensor<4, dim> &A) {
          const Tensor<1, dim> &a = fibre_field.at(copy.cell_index, q);
          if (!request.jacobian)
            P = material.stress(s.F[q], a);
          else
            {
              material.stress_and_tangent(s.F[q], a, P, A, method);
              if (project)
                materials::project_to_positive_definite(A);
            }
        },
        s,
        copy);
  }


  template <int dim>
  template <typename ScratchType, typename CopyType>
  void
  Solid<dim>::add_mean_dilatation_coupling(const ScratchType &s,
                                           CopyType          &copy) const
  {
    // The rank-two terms that couple every point through theta
    // (mean_dilatation.h).
    const unsigned int n_scalar = cache.n_scalar;
    for (unsigned int k = 0; k < n_scalar; ++k)
      for (unsigned int a = 0; a < dim; ++a)
        {
          const unsigned int i = cache.local_index[k * dim + a];
          for (unsigned int l = 0; l < n_scalar; ++l)
            for (unsigned int b = 0; b < dim; ++b)
              {
                const unsigned int j = cache.local_index[l * dim + b];
                if (j >= i)
                  copy.matrix(i, j) += s.C[k][a] * s.b[l][b]
                                       + s.b[k][a] * s.C[l][b]
                                       + s.Theta * s.b[k][a] * s.b[l][b];
              }
        }
  }


  template <int dim>
  template <typename ScratchType, typename CopyType>
  void
  Solid<dim>::add_edge_length_cell(const materials::Interface<dim> &material,
                                   const unsigned int               c,
                                   const bool                       jacobian,
                                   ScratchType                     &s,
                                   CopyType                        &copy) const
  {
    const double *JxW    = cache.JxW(c);
    double        volume = 0;
    for (unsigned int q = 0; q < cache.n_q; ++q)
      volume += JxW[q];
    const auto &cell = cache.cells()[c];
    for (unsigned int k = 0; k < cache.n_scalar; ++k)
      {
        s.vertices[k]  = cell->vertex(k);
        s.gradients[k] = cache.gradient(c, 0, k);
      }
    add_edge_length_element(s.vertices,
                            s.gradients,
                            volume,
                            s.U,
                            cache.local_index,
                            material,
                            fibre_field.at(copy.cell_index, 0),
                            copy.rhs,
                            jacobian ? &copy.matrix : nullptr);
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
    if (nodal && request.jacobian)
      prepare_nodal_jacobian();
    if (uses_lean_kernel(request))
      {
        assemble_lean(request, residual);
        return;
      }
    const bool edge_length = materials.edge_length_formulation();
    // The nodal dilatation's elastic part couples patches of cells: it is
    // added after the cells' loads and inertia.
    const bool patches = nodal != nullptr;
    const bool neumann
      = request.external && !boundary_conditions.neumann.empty();
    boundary_conditions.set_time(request.time);
    discretization.initialize_assembly_vector(residual);
    if (request.jacobian)
      jacobian_matrix = 0;

    // One cell: its elastic part (stresses at the points, or the
    // edge-length element), loads and inertia at the points, tractions on
    // its boundary faces. A cell with an inverted point where the model
    // cannot represent it contributes nothing; it is reported.
    auto worker = [&](const std::vector<unsigned int>::const_iterator &it,
                      Scratch<dim>                                    &s,
                      Copy                                            &copy) {
      const unsigned int c = *it;
      start_cell(request, c, s, copy);
      const auto &cell     = cache.cells()[c];
      const auto &material = materials.material(cell->material_id());
      if (request.internal && !patches)
        cell_deformation(request, material, c, s, copy);
      if (copy.inverted_det <= 0)
        return;
      const bool   elastic = request.internal && !edge_length && !patches;
      const double rho     = materials.density(cell->material_id());
      add_point_terms(request, material, c, rho, elastic, s, copy);
      if (elastic && request.jacobian
          && materials.mean_dilatation_formulation())
        add_mean_dilatation_coupling(s, copy);
      if (request.internal && edge_length)
        add_edge_length_cell(material, c, request.jacobian, s, copy);
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
                    Scratch<dim>(discretization, neumann),
                    Copy(cache.n_dofs));
    add_nodal_elastic(request, residual, inverted);
    add_contributions(request, residual);

    residual.compress(VectorOperation::add);
    if (request.jacobian)
      jacobian_matrix.compress(VectorOperation::add);
    if (request.jacobian && nodal_system)
      nodal_system->finish(&jacobian_matrix, residual);
    if (three_field.active() && request.internal)
      three_field.initialized();
    report_inversions(inverted);
  }


  template <int dim>
  void
  Solid<dim>::prepare_nodal_jacobian()
  {
    if (!nodal_system && !wide_layout)
      build_jacobian_matrix(true);
    if (nodal_system)
      nodal_system->clear();
  }


  template <int dim>
  void
  Solid<dim>::add_nodal_elastic(
    const Request                                             &request,
    VectorType                                                &residual,
    std::vector<std::tuple<unsigned int, double, Point<dim>>> &inverted,
    const bool                                                 loads)
  {
    if (!nodal || !request.internal)
      return;
    Assert(!loads || (nodal_system && request.jacobian), ExcInternalError());
    typename NodalDilatationSystem<dim>::Loads cell_loads;
    if (loads)
      {
        cell_loads.inertia          = request.inertia;
        cell_loads.mass_coefficient = request.mass_jacobian_coefficient;
        if (request.external)
          cell_loads.gravity
            = boundary_conditions.load_factor * boundary_conditions.gravity;
      }
    const auto undefined
      = nodal_system ? nodal_system->assemble(*request.u,
                                              materials,
                                              fibre_field,
                                              *request.rows,
                                              request.inhomogeneous,
                                              request.jacobian,
                                              residual,
                                              loads ? &cell_loads : nullptr)
                     : nodal->assemble(*request.u,
                                       materials,
                                       fibre_field,
                                       request.jacobian,
                                       *request.rows,
                                       request.inhomogeneous,
                                       jacobian_matrix,
                                       residual);
    inverted.insert(inverted.end(), undefined.begin(), undefined.end());
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
    if (materials.mean_dilatation_formulation())
      message << "; the mean dilatation formulation needs det F > 0 at every "
                 "quadrature point (its Fbar = (theta/J)^(1/d) F); use "
                 "'Formulation = displacement' with an invertible model for "
                 "scenes that invert elements";
    else
      message << "; the material model is undefined for det F <= 0 (use "
              << "'invertible neo-Hookean' or 'robust neo-Hookean' for scenes "
                 "that invert elements)";
    throw InvertedElementError(message.str());
  }


#define TISSUEFEM_INSTANTIATE(dim)                                            \
  template void Solid<dim>::assemble(const Request &, VectorType &);          \
  template void Solid<dim>::add_contributions(const Request &, VectorType &); \
  template void Solid<dim>::add_nodal_elastic(                                \
    const Request &,                                                          \
    VectorType &,                                                             \
    std::vector<std::tuple<unsigned int, double, Point<dim>>> &,              \
    const bool);                                                              \
  template void Solid<dim>::report_inversions(                                \
    const std::vector<std::tuple<unsigned int, double, Point<dim>>> &) const;

  TISSUEFEM_INSTANTIATE(1)
  TISSUEFEM_INSTANTIATE(2)
  TISSUEFEM_INSTANTIATE(3)
#undef TISSUEFEM_INSTANTIATE
} // namespace tissuefem::solid
