#include <deal.II/fe/fe_values_extractors.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/nan_aware.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/contact/penalty_contact.h>

#include <algorithm>
#include <cmath>

namespace tissuefem::contact
{
  template <int dim>
  void
  PenaltyContact<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Contact");
    prm.declare_entry(
      "Penalty factor",
      "100",
      Patterns::Double(0),
      "Dimensionless: the penalty stiffness per unit area is this times the "
      "largest Young's modulus of the materials over the diameter of the "
      "contact point's cell (stress / length units). The penetration under "
      "a contact pressure p is then p h / (factor E): at 100, a hundredth "
      "of the strain p / E the pressure causes, times the cell size. "
      "Larger is closer to no penetration and stiffer for Newton and for "
      "explicit steps. Must be > 0.");
    prm.leave_subsection();
  }


  template <int dim>
  PenaltyContact<dim>::PenaltyContact(
    ParameterHandler                 &prm,
    const solid::Discretization<dim> &discretization,
    std::vector<Obstacle<dim>>        obstacles,
    const double                      modulus)
      : discretization(discretization)
      , obstacle_list(std::move(obstacles))
      , modulus(modulus)
  {
    prm.enter_subsection("Contact");
    factor = prm.get_double("Penalty factor");
    prm.leave_subsection();
    require(factor > 0, "Contact/Penalty factor", "must be > 0");
  }


  template <int dim>
  void
  PenaltyContact<dim>::for_each_face(
    const VectorType                                       &u,
    const double                                            time,
    const std::function<void(const FEFaceValues<dim> &,
                             const std::vector<types::global_dof_index> &,
                             const std::vector<Point_> &)> &face) const
  {
    if (obstacle_list.empty())
      return;
    std::vector<Tensor<1, dim>> offsets;
    for (const auto &obstacle : obstacle_list)
      offsets.push_back(obstacle.offset(time));
    const auto                          &fe = *discretization.fe;
    FEFaceValues<dim>                    values(*discretization.mapping,
                             fe,
                             discretization.face_quadrature,
                             update_values | update_quadrature_points
                               | update_JxW_values);
    const FEValuesExtractors::Vector     displacement(0);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    std::vector<Tensor<1, dim>>          u_values;
    std::vector<Point_>                  points;
    for (const auto &cell : discretization.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && cell->at_boundary())
        for (const auto &f : cell->face_iterators())
          if (f->at_boundary())
            {
              values.reinit(cell, f);
              u_values.resize(values.n_quadrature_points);
              values[displacement].get_function_values(u, u_values);
              const double k = factor * modulus / cell->diameter();
              points.clear();
              for (unsigned int q = 0; q < values.n_quadrature_points; ++q)
                {
                  const Point<dim> x = values.quadrature_point(q) + u_values[q];
                  for (unsigned int o = 0; o < obstacle_list.size(); ++o)
                    {
                      const Gap<dim> gap = obstacle_list[o].gap(x, offsets[o]);
                      if (gap.distance <= 0)
                        points.push_back({o, gap, k, values.JxW(q), q});
                    }
                }
              if (points.empty())
                continue;
              cell->get_dof_indices(dofs);
              face(values, dofs, points);
            }
  }


  template <int dim>
  void
  PenaltyContact<dim>::add(const VectorType                &u,
                           const double                     time,
                           const bool                       jacobian,
                           const AffineConstraints<double> &rows,
                           const bool                       inhomogeneous,
                           MatrixType                      &matrix,
                           VectorType                      &residual) const
  {
    const FEValuesExtractors::Vector displacement(0);
    const unsigned int               n = discretization.fe->n_dofs_per_cell();
    FullMatrix<double>               K(n, n);
    Vector<double>                   r(n);
    std::vector<Tensor<1, dim>>      phi(n);
    auto                             face = [&](const FEFaceValues<dim>                    &values,
                    const std::vector<types::global_dof_index> &dofs,
                    const std::vector<Point_>                  &points) {
      K = 0;
      r = 0;
      for (const Point_ &p : points)
        {
          const double weight = p.k * p.area;
          for (unsigned int i = 0; i < n; ++i)
            phi[i] = values[displacement].value(i, p.q);
          for (unsigned int i = 0; i < n; ++i)
            {
              const double n_i = p.gap.normal * phi[i];
              // dE/du_i = k g dg/du_i, dg/du_i = n . phi_i.
              r(i) += weight * p.gap.distance * n_i;
              if (jacobian)
                for (unsigned int j = 0; j < n; ++j)
                  K(i, j)
                    += weight
                       * (n_i * (p.gap.normal * phi[j])
                          + p.gap.distance
                              * (phi[i] * (p.gap.normal_gradient * phi[j])));
            }
        }
      if (jacobian)
        rows.distribute_local_to_global(
          K, r, dofs, matrix, residual, inhomogeneous);
      else
        rows.distribute_local_to_global(r, dofs, residual);
    };
    for_each_face(u, time, face);
  }


  template <int dim>
  double
  PenaltyContact<dim>::energy(const VectorType &u, const double time) const
  {
    double sum  = 0;
    auto   face = [&](const FEFaceValues<dim> &,
                    const std::vector<types::global_dof_index> &,
                    const std::vector<Point_> &points) {
      for (const Point_ &p : points)
        sum += 0.5 * p.k * p.area * p.gap.distance * p.gap.distance;
    };
    for_each_face(u, time, face);
    return Utilities::MPI::sum(sum, parallel_tools::communicator());
  }


  template <int dim>
  std::vector<typename PenaltyContact<dim>::Report>
  PenaltyContact<dim>::report(const VectorType &u, const double time) const
  {
    const unsigned int  m = obstacle_list.size();
    std::vector<double> sums(m * (dim + 1), 0.), deepest(m, 0.);
    auto                face = [&](const FEFaceValues<dim> &,
                    const std::vector<types::global_dof_index> &,
                    const std::vector<Point_> &points) {
      for (const Point_ &p : points)
        if (p.gap.distance < 0)
          {
            double *s = &sums[p.obstacle * (dim + 1)];
            for (unsigned int d = 0; d < dim; ++d)
              s[d] -= p.k * p.area * p.gap.distance * p.gap.normal[d];
            s[dim] += p.area;
            deepest[p.obstacle]
              = max_keeping_nan(deepest[p.obstacle], -p.gap.distance);
          }
    };
    for_each_face(u, time, face);
    const MPI_Comm comm = parallel_tools::communicator();
    Utilities::MPI::sum(sums, comm, sums);
    for (double &d : deepest)
      d = mpi_max_keeping_nan(d, comm);
    std::vector<Report> result(m);
    for (unsigned int o = 0; o < m; ++o)
      {
        result[o].name = obstacle_list[o].name;
        for (unsigned int d = 0; d < dim; ++d)
          result[o].force[d] = sums[o * (dim + 1) + d];
        result[o].area        = sums[o * (dim + 1) + dim];
        result[o].penetration = deepest[o];
      }
    return result;
  }


  template class PenaltyContact<1>;
  template class PenaltyContact<2>;
  template class PenaltyContact<3>;
} // namespace tissuefem::contact
