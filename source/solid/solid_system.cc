#include <deal.II/base/function.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/numerics/vector_tools.h>

#include <tissuefem/solid/solid_system.h>

#include <cmath>
#include <limits>
#include <map>
#include <sstream>

namespace tissuefem::solid
{
  namespace
  {
    /// Calls @p f(cell, F at q, JxW) for every quadrature point.
    template <int dim, typename Callback>
    void
    for_each_deformation_gradient(const Discretization<dim> &discretization,
                                  const Vector<double>      &u,
                                  const Callback            &f)
    {
      FEValues<dim>                    fe_values(*discretization.mapping,
                              *discretization.fe,
                              discretization.cell_quadrature,
                              update_gradients | update_JxW_values);
      const FEValuesExtractors::Vector displacement(0);
      std::vector<Tensor<2, dim>> grad_u(discretization.cell_quadrature.size());
      for (const auto &cell :
           discretization.dof_handler.active_cell_iterators())
        {
          fe_values.reinit(cell);
          fe_values[displacement].get_function_gradients(u, grad_u);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            f(cell,
              q,
              unit_symmetric_tensor<dim>() + grad_u[q],
              fe_values.JxW(q));
        }
    }
  } // namespace


  template <int dim>
  SolidSystem<dim>::SolidSystem(
    const Discretization<dim>         &discretization,
    const materials::MaterialSet<dim> &materials,
    boundary::BoundaryConditions<dim> &boundary_conditions)
      : discretization(discretization)
      , materials(materials)
      , boundary_conditions(boundary_conditions)
  {
    const auto &dof_handler = discretization.dof_handler;
    for (const auto &d : boundary_conditions.dirichlet)
      VectorTools::interpolate_boundary_values(*discretization.mapping,
                                               dof_handler,
                                               d.id,
                                               Functions::ZeroFunction<dim>(
                                                 dim),
                                               constraints,
                                               d.mask);
    constraints.close();

    DynamicSparsityPattern dsp(dof_handler.n_dofs());
    DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, false);
    sparsity.copy_from(dsp);
    tangent_matrix.reinit(sparsity);

    // The body force is evaluated at every quadrature point unless its
    // expressions are literally zero.
    body_force_present = !boundary_conditions.body_force_is_zero;

    if (materials.edge_length_formulation())
      require(discretization.simplex && discretization.fe->degree == 1,
              "Materials/Formulation",
              "'edge length' needs linear simplices (Geometry/Cell type = "
              "simplex or a simplex mesh file, Polynomial degree = 1)");

    if (materials.any_uses_fibres())
      {
        FEValues<dim>      fe_values(*discretization.mapping,
                                *discretization.fe,
                                discretization.cell_quadrature,
                                update_quadrature_points);
        const unsigned int n_q = discretization.cell_quadrature.size();
        fibres.resize(dof_handler.get_triangulation().n_active_cells() * n_q);
        for (const auto &cell : dof_handler.active_cell_iterators())
          {
            fe_values.reinit(cell);
            Tensor<1, dim> mean;
            for (unsigned int q = 0; q < n_q; ++q)
              {
                fibres[cell->active_cell_index() * n_q + q]
                  = materials.fibre_direction(fe_values.quadrature_point(q));
                mean += fibres[cell->active_cell_index() * n_q + q];
              }
            // The edge-length element has one fibre per element; use the
            // same (normalized mean) direction at every quadrature point so
            // that energies and stresses reported afterwards belong to the
            // problem solved.
            if (materials.edge_length_formulation() && mean.norm() > 0)
              for (unsigned int q = 0; q < n_q; ++q)
                fibres[cell->active_cell_index() * n_q + q]
                  = mean / mean.norm();
          }
      }
  }


  template <int dim>
  const Tensor<1, dim> &
  SolidSystem<dim>::fibre(const unsigned int cell_index,
                          const unsigned int q) const
  {
    // Isotropic models ignore the direction; any unit vector will do.
    static const Tensor<1, dim> unused = [] {
      Tensor<1, dim> e;
      e[0] = 1.;
      return e;
    }();
    if (fibres.empty())
      return unused;
    return fibres[cell_index * discretization.cell_quadrature.size() + q];
  }


  template <int dim>
  void
  SolidSystem<dim>::check_not_inverted(
    const double                     J,
    const materials::Interface<dim> &material,
    const Vector<double>            &u) const
  {
    if (J > 0 || material.admits_inversion())
      return;
    // Name every inverted cell (up to a few), not just the first found.
    std::vector<std::pair<unsigned int, Point<dim>>> inverted;
    double                                           smallest = 0;
    for_each_deformation_gradient(
      discretization,
      u,
      [&](const auto &cell, unsigned int, const Tensor<2, dim> &F, double) {
        const double det = determinant(F);
        if (det <= 0
            && !materials.material(cell->material_id()).admits_inversion()
            && (inverted.empty()
                || inverted.back().first != cell->active_cell_index()))
          inverted.emplace_back(cell->active_cell_index(), cell->center());
        smallest = std::min(smallest, det);
      });
    std::ostringstream message;
    message << inverted.size()
            << " element(s) inverted (smallest det F = " << smallest
            << "): cell";
    for (unsigned int i = 0; i < std::min<std::size_t>(inverted.size(), 4); ++i)
      message << (i ? ", " : " ") << inverted[i].first << " at ("
              << inverted[i].second << ")";
    if (inverted.size() > 4)
      message << ", ...";
    message << "; the material model is undefined for det F <= 0 (use "
            << "'robust neo-Hookean' for scenes that invert elements)";
    throw InvertedElementError(message.str());
  }


  template <int dim>
  void
  SolidSystem<dim>::assemble(const Vector<double> &u,
                             const Vector<double> &u_tilde,
                             const double          mass_coefficient,
                             const double          time,
                             Vector<double>       &residual,
                             const bool            with_tangent)
  {
    assemble_with(
      constraints, u, u_tilde, mass_coefficient, time, residual, with_tangent);
  }


  template <int dim>
  std::vector<Tensor<1, dim>>
  SolidSystem<dim>::reaction_forces(
    const Vector<double>                  &u,
    const Vector<double>                  &u_tilde,
    const double                           mass_coefficient,
    const double                           time,
    const std::vector<types::boundary_id> &boundary_ids)
  {
    std::vector<Tensor<1, dim>> forces(boundary_ids.size());
    if (boundary_ids.empty())
      return forces;
    no_constraints.close();
    Vector<double> residual;
    assemble_with(
      no_constraints, u, u_tilde, mass_coefficient, time, residual, false);
    const auto &dof_handler = discretization.dof_handler;
    for (unsigned int b = 0; b < boundary_ids.size(); ++b)
      for (unsigned int c = 0; c < dim; ++c)
        {
          std::vector<bool> mask(dim, false);
          mask[c] = true;
          const IndexSet dofs
            = DoFTools::extract_boundary_dofs(dof_handler,
                                              ComponentMask(mask),
                                              {boundary_ids[b]});
          for (const auto dof : dofs)
            forces[b][c] += residual[dof];
        }
    return forces;
  }


  template <int dim>
  void
  SolidSystem<dim>::assemble_with(
    const AffineConstraints<double> &row_constraints,
    const Vector<double>            &u,
    const Vector<double>            &u_tilde,
    const double                     mass_coefficient,
    const double                     time,
    Vector<double>                  &residual,
    const bool                       with_tangent)
  {
    const auto        &fe = *discretization.fe;
    const unsigned int n  = fe.n_dofs_per_cell();
    FEValues<dim>      fe_values(*discretization.mapping,
                            fe,
                            discretization.cell_quadrature,
                            update_values | update_gradients | update_JxW_values
                              | (body_force_present ? update_quadrature_points
                                                         : update_default));
    FEFaceValues<dim>  fe_face_values(*discretization.mapping,
                                     fe,
                                     discretization.face_quadrature,
                                     update_values | update_quadrature_points
                                       | update_JxW_values);

    boundary_conditions.set_time(time);
    residual.reinit(n_dofs());
    if (with_tangent)
      tangent_matrix = 0;

    FullMatrix<double>                   cell_matrix(n, n);
    Vector<double>                       cell_rhs(n);
    std::vector<types::global_dof_index> dofs(n);
    std::vector<double>                  u_cell(n), inertia_cell(n);
    std::vector<unsigned int>            component(n);
    for (unsigned int i = 0; i < n; ++i)
      component[i] = fe.system_to_component_index(i).first;
    std::vector<Tensor<1, dim>> grads(n);
    std::vector<double>         values(n);
    Vector<double>              body_force(dim), traction(dim);
    Tensor<2, dim>              P;
    Tensor<4, dim>              A;
    const auto                  method = materials.tangent_method();
    const bool edge_length             = materials.edge_length_formulation();

    for (const auto &cell : discretization.dof_handler.active_cell_iterators())
      {
        fe_values.reinit(cell);
        cell->get_dof_indices(dofs);
        for (unsigned int i = 0; i < n; ++i)
          {
            u_cell[i]       = u[dofs[i]];
            inertia_cell[i] = u[dofs[i]] - u_tilde[dofs[i]];
          }
        const auto  &material = materials.material(cell->material_id());
        const double rho      = materials.density(cell->material_id());
        cell_matrix           = 0;
        cell_rhs              = 0;

        for (const unsigned int q : fe_values.quadrature_point_indices())
          {
            const double   JxW = fe_values.JxW(q);
            Tensor<2, dim> F   = unit_symmetric_tensor<dim>();
            Tensor<1, dim> inertia;
            for (unsigned int i = 0; i < n; ++i)
              {
                grads[i]  = fe_values.shape_grad(i, q);
                values[i] = fe_values.shape_value(i, q);
                F[component[i]] += u_cell[i] * grads[i];
                inertia[component[i]] += inertia_cell[i] * values[i];
              }
            check_not_inverted(determinant(F), material, u);
            const Tensor<1, dim> &a = fibre(cell->active_cell_index(), q);
            if (edge_length)
              {
                // The element's elastic forces come from its edge lengths
                // below; here only loads and inertia.
                P = 0;
                A = 0;
              }
            else if (with_tangent)
              material.stress_and_tangent(F, a, P, A, method);
            else
              P = material.stress(F, a);

            Tensor<1, dim> load = rho * boundary_conditions.gravity;
            if (body_force_present)
              {
                boundary_conditions.body_force->vector_value(
                  fe_values.quadrature_point(q), body_force);
                for (unsigned int d = 0; d < dim; ++d)
                  load[d] += body_force[d];
              }
            // The inertial term c rho (u - u_tilde) acts like a load.
            load -= mass_coefficient * rho * inertia;

            for (unsigned int i = 0; i < n; ++i)
              {
                const unsigned int ci = component[i];
                cell_rhs[i] += (P[ci] * grads[i] - load[ci] * values[i]) * JxW;
                if (!with_tangent)
                  continue;
                // B_lm = A_{ci k l m} dN_i/dX_k, so that
                // K_ij = B_{cj m} dN_j/dX_m (problem session eq 19).
                Tensor<2, dim> B;
                for (unsigned int k = 0; k < dim; ++k)
                  B += grads[i][k] * A[ci][k];
                const double mass_i = mass_coefficient * rho * values[i];
                for (unsigned int j = i; j < n; ++j)
                  {
                    double value = B[component[j]] * grads[j];
                    if (component[j] == ci)
                      value += mass_i * values[j];
                    cell_matrix(i, j) += value * JxW;
                  }
              }
          }

        if (edge_length)
          add_edge_length_element(cell,
                                  fe_values,
                                  u_cell,
                                  material,
                                  cell_rhs,
                                  with_tangent ? &cell_matrix : nullptr);

        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            for (const auto &neumann : boundary_conditions.neumann)
              if (face->boundary_id() == neumann.id)
                {
                  fe_face_values.reinit(cell, face);
                  for (const unsigned int q :
                       fe_face_values.quadrature_point_indices())
                    {
                      neumann.traction->vector_value(
                        fe_face_values.quadrature_point(q), traction);
                      for (unsigned int i = 0; i < n; ++i)
                        cell_rhs[i] -= traction[component[i]]
                                       * fe_face_values.shape_value(i, q)
                                       * fe_face_values.JxW(q);
                    }
                }

        if (with_tangent)
          {
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < i; ++j)
                cell_matrix(i, j) = cell_matrix(j, i);
            row_constraints.distribute_local_to_global(
              cell_matrix, cell_rhs, dofs, tangent_matrix, residual);
          }
        else
          row_constraints.distribute_local_to_global(cell_rhs, dofs, residual);
      }
  }


  template <int dim>
  void
  SolidSystem<dim>::add_edge_length_element(
    const typename DoFHandler<dim>::active_cell_iterator &cell,
    const FEValues<dim>                                  &fe_values,
    const std::vector<double>                            &u_cell,
    const materials::Interface<dim>                      &material,
    Vector<double>                                       &cell_rhs,
    FullMatrix<double>                                   *cell_matrix) const
  {
    // For P1 simplices, shape function i belongs to vertex
    // system_to_component_index(i).second; the element's unknowns are
    // indexed vertex * dim + component.
    const auto                 &fe = *discretization.fe;
    const unsigned int          n  = fe.n_dofs_per_cell();
    std::vector<unsigned int>   element_index(n);
    std::vector<Tensor<1, dim>> alpha(dim + 1), Q(dim + 1);
    for (unsigned int v = 0; v <= dim; ++v)
      Q[v] = cell->vertex(v);
    for (unsigned int i = 0; i < n; ++i)
      {
        const auto [component, vertex] = fe.system_to_component_index(i);
        element_index[i]               = vertex * dim + component;
        Q[vertex][component] += u_cell[i];
        if (component == 0)
          alpha[vertex] = fe_values.shape_grad(i, 0);
      }
    double volume = 0;
    for (const unsigned int q : fe_values.quadrature_point_indices())
      volume += fe_values.JxW(q);

    double              energy;
    std::vector<double> forces, stiffness;
    material.edge_length_element(alpha,
                                 volume,
                                 Q,
                                 fibre(cell->active_cell_index(), 0),
                                 energy,
                                 forces,
                                 cell_matrix ? &stiffness : nullptr);
    for (unsigned int i = 0; i < n; ++i)
      {
        cell_rhs[i] += forces[element_index[i]];
        if (cell_matrix)
          for (unsigned int j = i; j < n; ++j)
            (*cell_matrix)(i, j)
              += stiffness[element_index[i] * n + element_index[j]];
      }
  }


  template <int dim>
  void
  SolidSystem<dim>::apply_dirichlet_values(const double time, Vector<double> &u)
  {
    std::map<types::global_dof_index, double> values;
    for (auto &d : boundary_conditions.dirichlet)
      {
        d.displacement->set_time(time);
        VectorTools::interpolate_boundary_values(*discretization.mapping,
                                                 discretization.dof_handler,
                                                 d.id,
                                                 *d.displacement,
                                                 values,
                                                 d.mask);
      }
    for (const auto &[dof, value] : values)
      u[dof] = value;
  }


  template <int dim>
  void
  SolidSystem<dim>::initial_state(Vector<double> &u, Vector<double> &v) const
  {
    u.reinit(n_dofs());
    v.reinit(n_dofs());
    boundary_conditions.initial_displacement->set_time(0);
    boundary_conditions.initial_velocity->set_time(0);
    VectorTools::interpolate(*discretization.mapping,
                             discretization.dof_handler,
                             *boundary_conditions.initial_displacement,
                             u);
    VectorTools::interpolate(*discretization.mapping,
                             discretization.dof_handler,
                             *boundary_conditions.initial_velocity,
                             v);
  }


  template <int dim>
  void
  SolidSystem<dim>::cell_fields(const Vector<double> &u,
                                Vector<float>        &jacobian,
                                Vector<float>        &von_mises) const
  {
    const auto  &triangulation = discretization.dof_handler.get_triangulation();
    const double n_q           = discretization.cell_quadrature.size();
    jacobian.reinit(triangulation.n_active_cells());
    von_mises.reinit(triangulation.n_active_cells());
    for_each_deformation_gradient(
      discretization,
      u,
      [&](const auto &cell, unsigned int q, const Tensor<2, dim> &F, double) {
        const double J = determinant(F);
        jacobian[cell->active_cell_index()] += J / n_q;
        if (J <= 0
            && !materials.material(cell->material_id()).admits_inversion())
          return;
        const Tensor<2, dim> P
          = materials.material(cell->material_id())
              .stress(F, fibre(cell->active_cell_index(), q));
        const Tensor<2, dim> sigma = (J != 0 ? 1. / J : 0.) * P * transpose(F);
        const double         mean  = trace(sigma) / dim;
        Tensor<2, dim>       deviator = sigma;
        for (unsigned int d = 0; d < dim; ++d)
          deviator[d][d] -= mean;
        // In 1D the only stress is uniaxial, whose von Mises value is
        // |sigma|; in 2D the in-plane (2 x 2) stress is used.
        von_mises[cell->active_cell_index()]
          += (dim == 1 ? std::abs(sigma[0][0])
                       : std::sqrt(1.5 * scalar_product(deviator, deviator)))
             / n_q;
      });
  }


  template <int dim>
  double
  SolidSystem<dim>::elastic_energy(const Vector<double> &u) const
  {
    double energy = 0;
    for_each_deformation_gradient(
      discretization,
      u,
      [&](
        const auto &cell, unsigned int q, const Tensor<2, dim> &F, double JxW) {
        energy += materials.material(cell->material_id())
                    .energy_density(F, fibre(cell->active_cell_index(), q))
                  * JxW;
      });
    return energy;
  }


  template <int dim>
  std::vector<Vector<float>>
  SolidSystem<dim>::cell_fibre_directions() const
  {
    std::vector<Vector<float>> result;
    if (fibres.empty())
      return result;
    const auto &triangulation = discretization.dof_handler.get_triangulation();
    const unsigned int n_q    = discretization.cell_quadrature.size();
    result.assign(dim, Vector<float>(triangulation.n_active_cells()));
    for (unsigned int c = 0; c < triangulation.n_active_cells(); ++c)
      {
        Tensor<1, dim> mean;
        for (unsigned int q = 0; q < n_q; ++q)
          mean += fibres[c * n_q + q];
        mean /= std::max(mean.norm(), 1e-300);
        for (unsigned int d = 0; d < dim; ++d)
          result[d][c] = mean[d];
      }
    return result;
  }

  template <int dim>
  double
  SolidSystem<dim>::min_jacobian(const Vector<double> &u) const
  {
    double smallest = std::numeric_limits<double>::max();
    for_each_deformation_gradient(
      discretization,
      u,
      [&](const auto &, unsigned int, const Tensor<2, dim> &F, double) {
        smallest = std::min(smallest, determinant(F));
      });
    return smallest;
  }


  template <int dim>
  double
  SolidSystem<dim>::distance_from_rest_shape(const Vector<double> &u) const
  {
    // Reference and deformed positions of the vertices.
    const auto &dof_handler = discretization.dof_handler;
    std::map<unsigned int, std::pair<Point<dim>, Point<dim>>> vertices;
    for (const auto &cell : dof_handler.active_cell_iterators())
      for (const unsigned int v : cell->vertex_indices())
        {
          Point<dim> x = cell->vertex(v);
          for (unsigned int c = 0; c < dim; ++c)
            x[c] += u[cell->vertex_dof_index(v, c)];
          vertices[cell->vertex_index(v)] = {cell->vertex(v), x};
        }
    Point<dim> X_mean, x_mean;
    for (const auto &[index, pair] : vertices)
      {
        X_mean += pair.first / double(vertices.size());
        x_mean += pair.second / double(vertices.size());
      }
    // R maximizes sum (x - x_mean) . R (X - X_mean): R = U diag(1, .., det)
    // V^T from the SVD M = U S V^T of M = sum (x - x_mean) (x) (X - X_mean).
    LAPACKFullMatrix<double> M(dim, dim);
    for (const auto &[index, pair] : vertices)
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          M(i, j) += (pair.second[i] - x_mean[i]) * (pair.first[j] - X_mean[j]);
    M.compute_svd();
    const auto    &U = M.get_svd_u();
    const auto    &V = M.get_svd_vt();
    Tensor<2, dim> Ut, Vt;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        {
          Ut[i][j] = U(i, j);
          Vt[i][j] = V(i, j);
        }
    Tensor<2, dim> D              = unit_symmetric_tensor<dim>();
    D[dim - 1][dim - 1]           = determinant(Ut * Vt) < 0 ? -1. : 1.;
    const Tensor<2, dim> R        = Ut * D * Vt;
    double               distance = 0;
    for (const auto &[index, pair] : vertices)
      distance
        = std::max(distance,
                   (x_mean + R * (pair.first - X_mean) - pair.second).norm());
    return distance;
  }

  template class SolidSystem<1>;
  template class SolidSystem<2>;
  template class SolidSystem<3>;
} // namespace tissuefem::solid
