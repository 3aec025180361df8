#include <deal.II/fe/fe_values.h>

#include <tissuefem/contact/boundary_points.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tissuefem::contact
{
  template <int dim>
  BoundaryPoints<dim>::BoundaryPoints(
    const solid::Discretization<dim> &discretization)
      : discretization(discretization)
  {
    const auto &fe = *discretization.fe;
    n_q            = discretization.face_quadrature.size();
    n_dofs         = fe.n_dofs_per_cell();
    for (unsigned int i = 0; i < n_dofs; ++i)
      component.push_back(fe.system_to_component_index(i).first);
    mesh_changed = discretization.dof_handler.get_triangulation()
                     .signals.any_change.connect([this]() { stale = true; });
  }


  template <int dim>
  const std::vector<typename BoundaryPoints<dim>::Face> &
  BoundaryPoints<dim>::faces() const
  {
    if (stale || built_for_dofs != discretization.dof_handler.n_dofs())
      build();
    return face_list;
  }


  template <int dim>
  void
  BoundaryPoints<dim>::build() const
  {
    face_list.clear();
    positions.clear();
    weights.clear();
    values.clear();
    dof_indices.clear();
    FEFaceValues<dim>                    fe_values(*discretization.mapping,
                                *discretization.fe,
                                discretization.face_quadrature,
                                update_values | update_quadrature_points
                                  | update_JxW_values);
    std::vector<types::global_dof_index> dofs(n_dofs);
    for (const auto &cell : discretization.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && cell->at_boundary())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              fe_values.reinit(cell, f);
              const std::uint64_t key
                = (std::uint64_t(cell->active_cell_index())
                     * GeometryInfo<dim>::faces_per_cell
                   + f)
                  * n_q;
              face_list.push_back(
                {key,
                 cell->diameter(),
                 static_cast<unsigned int>(positions.size()),
                 static_cast<unsigned int>(dof_indices.size())});
              cell->get_dof_indices(dofs);
              dof_indices.insert(dof_indices.end(), dofs.begin(), dofs.end());
              for (unsigned int q = 0; q < n_q; ++q)
                {
                  positions.push_back(fe_values.quadrature_point(q));
                  weights.push_back(fe_values.JxW(q));
                  for (unsigned int i = 0; i < n_dofs; ++i)
                    values.push_back(
                      fe_values.shape_value_component(i, q, component[i]));
                }
            }
    // L: the largest sum of |phi_i| of one component at a point.
    lebesgue = 1;
    for (unsigned int p = 0; p < positions.size(); ++p)
      for (unsigned int c = 0; c < dim; ++c)
        {
          double sum = 0;
          for (unsigned int i = 0; i < n_dofs; ++i)
            if (component[i] == c)
              sum += std::abs(values[p * n_dofs + i]);
          lebesgue = std::max(lebesgue, sum);
        }
    local_index.clear();
    ++builds;
    stale          = false;
    built_for_dofs = discretization.dof_handler.n_dofs();
  }


  template <int dim>
  void
  BoundaryPoints<dim>::index(const VectorType &u) const
  {
    const auto &vector = u.trilinos_vector();
    if (local_index.size() == dof_indices.size()
        && indexed_length == vector.MyLength())
      return;
    indexed_length = vector.MyLength();
    local_index.resize(dof_indices.size());
    for (unsigned int k = 0; k < dof_indices.size(); ++k)
      {
        local_index[k] = vector.Map().LID(
          static_cast<TrilinosWrappers::types::int_type>(dof_indices[k]));
        AssertThrow(local_index[k] >= 0,
                    ExcMessage("contact: a boundary face's degree of "
                               "freedom is not in the ghosted vector"));
      }
    ++builds;
    distinct_local = local_index;
    std::sort(distinct_local.begin(), distinct_local.end());
    distinct_local.erase(std::unique(distinct_local.begin(),
                                     distinct_local.end()),
                         distinct_local.end());
  }


  template <int dim>
  void
  BoundaryPoints<dim>::prepare(const VectorType &u) const
  {
    faces();
    index(u);
  }


  template <int dim>
  void
  BoundaryPoints<dim>::values_of(const VectorType    &u,
                                 std::vector<double> &reference) const
  {
    faces();
    index(u);
    const double *entries = u.trilinos_vector()[0];
    reference.resize(distinct_local.size());
    for (unsigned int k = 0; k < distinct_local.size(); ++k)
      reference[k] = entries[distinct_local[k]];
  }


  template <int dim>
  double
  BoundaryPoints<dim>::motion_bound(const VectorType          &u,
                                    const std::vector<double> &reference) const
  {
    faces();
    index(u);
    AssertDimension(reference.size(), distinct_local.size());
    const double *entries = u.trilinos_vector()[0];
    double        largest = 0;
    for (unsigned int k = 0; k < distinct_local.size(); ++k)
      {
        const double change
          = std::abs(entries[distinct_local[k]] - reference[k]);
        // A displacement that is not finite bounds nothing: every face is
        // then evaluated (and Newton's checks see it).
        if (!std::isfinite(change))
          return std::numeric_limits<double>::infinity();
        largest = std::max(largest, change);
      }
    return std::sqrt(double(dim)) * lebesgue * largest;
  }


  template <int dim>
  void
  BoundaryPoints<dim>::deformed(const Face              &face,
                                const VectorType        &u,
                                std::vector<Point<dim>> &x) const
  {
    // Every ghosted vector of the discretization lays out its entries
    // alike (as the lean kernel's ghost indices assume): the positions of
    // the faces' entries are looked up once per mesh.
    const auto &vector = u.trilinos_vector();
    index(u);
    local.resize(n_dofs);
    const double *entries = vector[0];
    const int    *where   = &local_index[face.first_dof];
    for (unsigned int i = 0; i < n_dofs; ++i)
      local[i] = entries[where[i]];
    x.resize(n_q);
    for (unsigned int q = 0; q < n_q; ++q)
      {
        x[q]                = positions[face.first_point + q];
        const double *shape = &values[(face.first_point + q) * n_dofs];
        for (unsigned int i = 0; i < n_dofs; ++i)
          x[q][component[i]] += local[i] * shape[i];
      }
  }


  template class BoundaryPoints<1>;
  template class BoundaryPoints<2>;
  template class BoundaryPoints<3>;
} // namespace tissuefem::contact
