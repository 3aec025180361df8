#include <deal.II/fe/fe_values_extractors.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/nan_aware.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/contact/coulomb.h>
#include <tissuefem/contact/penalty_contact.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>

namespace tissuefem::contact
{
  template <int dim>
  void
  PenaltyContact<dim>::add_stiffness_bound(VectorType &row_sums) const
  {
    if (obstacle_list.empty())
      return;
    const auto                          &fe = *discretization.fe;
    FEFaceValues<dim>                    values(*discretization.mapping,
                             fe,
                             discretization.face_quadrature,
                             update_values | update_JxW_values);
    const FEValuesExtractors::Vector     displacement(0);
    const unsigned int                   n = fe.n_dofs_per_cell();
    std::vector<types::global_dof_index> dofs(n);
    Vector<double>                       sums(n);
    std::vector<double>                  size(n);
    AffineConstraints<double>            none;
    none.close();
    // max over unit n of max_c |n_c| sum_d |n_d|; a point may touch every
    // obstacle at once.
    const double normal = (1 + std::sqrt(double(dim))) / 2;
    // Friction's tangent k_t P, P = I - n (x) n: |P_cd| <= 1 off and on
    // the diagonal's 1 - n_c^2, so a row of P sums to at most 1 + |n_c|
    // sum_d |n_d|.
    const double bound
      = (normal + (has_friction() ? tangential * (1 + normal) : 0.))
        * obstacle_list.size();
    for (const auto &cell : discretization.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && cell->at_boundary())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              values.reinit(cell, f);
              const double k = factor * modulus / cell->diameter();
              sums           = 0;
              for (unsigned int q = 0; q < values.n_quadrature_points; ++q)
                {
                  double total = 0;
                  for (unsigned int i = 0; i < n; ++i)
                    total += size[i] = values[displacement].value(i, q).norm();
                  // Each scalar shape function is there once per component.
                  for (unsigned int i = 0; i < n; ++i)
                    sums(i)
                      += bound * k * values.JxW(q) * size[i] * total / dim;
                }
              cell->get_dof_indices(dofs);
              none.distribute_local_to_global(sums, dofs, row_sums);
            }
  }


  template <int dim>
  Coulomb<dim>
  PenaltyContact<dim>::friction(const Point_ &p) const
  {
    // The slip and tau are kept in the obstacle's frame, so that a stuck
    // point's stick point turns with a rotating obstacle; the law takes
    // them in the world's (only y - a enters it).
    return Coulomb<dim>(Point<dim>(p.pose->world_vector(p.y - *p.anchor)),
                        Point<dim>(),
                        p.gap.normal,
                        tangential * p.k,
                        p.bound,
                        p.pose->world_vector(p.tau));
  }


  template <int dim>
  bool
  PenaltyContact<dim>::has_friction() const
  {
    for (const auto &obstacle : obstacle_list)
      if (obstacle.friction > 0)
        return true;
    return false;
  }


  template <int dim>
  std::vector<Pose<dim>>
  PenaltyContact<dim>::poses_at(const double time) const
  {
    std::vector<Pose<dim>> poses;
    for (const auto &obstacle : obstacle_list)
      poses.push_back(obstacle.pose(time));
    return poses;
  }


  namespace
  {
    /// The ball around a face's points @p x: their centre and the largest
    /// distance from it (length units).
    template <int dim>
    std::pair<Point<dim>, double>
    ball_around(const std::vector<Point<dim>> &x)
    {
      Point<dim> centre;
      for (const Point<dim> &p : x)
        centre += p / double(x.size());
      double radius = 0;
      for (const Point<dim> &p : x)
        radius = std::max(radius, p.distance(centre));
      return {centre, radius};
    }


    template <int dim>
    bool
    same_poses(const std::vector<Pose<dim>> &a, const std::vector<Pose<dim>> &b)
    {
      if (a.size() != b.size())
        return false;
      for (unsigned int o = 0; o < a.size(); ++o)
        if (a[o].translation != b[o].translation
            || a[o].rotation != b[o].rotation || a[o].pivot != b[o].pivot)
          return false;
      return true;
    }
  } // namespace


  template <int dim>
  void
  PenaltyContact<dim>::update_broad_phase(const VectorType             &u,
                                          const std::vector<Pose<dim>> &poses,
                                          const double largest_multiplier,
                                          double      &motion) const
  {
    const auto &faces = boundary.faces();
    auto       &kept  = broad_phase;
    // NaN refits, and the NaN balls then keep every node that holds them.
    motion                = std::numeric_limits<double>::quiet_NaN();
    const bool same_faces = kept.generation == boundary.generation()
                            && kept.keys.size() == faces.size();
    if (same_faces)
      motion = boundary.motion_bound(u, kept.reference);
    if (!(motion <= kept.limit))
      {
        boundary.values_of(u, kept.reference);
        std::vector<Point<dim>> centres(faces.size()), x;
        std::vector<double>     radii(faces.size()), sizes(faces.size());
        for (unsigned int i = 0; i < faces.size(); ++i)
          {
            boundary.deformed(faces[i], u, x);
            std::tie(centres[i], radii[i]) = ball_around(x);
            sizes[i]                       = faces[i].diameter;
          }
        if (same_faces)
          kept.tree.refit(centres, radii);
        else
          {
            kept.tree.build(centres, radii, sizes);
            kept.generation = boundary.generation();
            kept.keys.clear();
            double diameters = 0;
            for (const Face &f : faces)
              {
                kept.keys.push_back(f.key);
                diameters += f.diameter;
              }
            kept.limit = faces.empty() ? 0 : 0.25 * diameters / faces.size();
          }
        ++kept.fits;
        motion = 0;
      }
    if (kept.queried_fit == kept.fits && same_poses(kept.queried_poses, poses)
        && kept.queried_multiplier == largest_multiplier)
      return;
    // A point acts where lambda - k g >= 0 with k = factor E / h, so
    // nowhere on a face whose gaps exceed largest_multiplier h / (factor
    // E): the tree's threshold per unit of face diameter; its margin, the
    // motion the fit allows.
    kept.faces.clear();
    const double per_size = largest_multiplier / (factor * modulus);
    for (unsigned int o = 0; o < obstacle_list.size(); ++o)
      kept.tree.near(
        [&](const Point<dim> &y) {
          return obstacle_list[o].distance(y, poses[o]);
        },
        kept.limit,
        per_size,
        kept.faces);
    std::sort(kept.faces.begin(), kept.faces.end());
    kept.faces.erase(std::unique(kept.faces.begin(), kept.faces.end()),
                     kept.faces.end());
    const unsigned int n_obs = obstacle_list.size();
    kept.lower.resize(kept.faces.size() * n_obs);
    for (unsigned int j = 0; j < kept.faces.size(); ++j)
      for (unsigned int o = 0; o < n_obs; ++o)
        kept.lower[j * n_obs + o]
          = obstacle_list[o].distance(kept.tree.centre_of(kept.faces[j]),
                                      poses[o])
            - kept.tree.radius_of(kept.faces[j]);
    kept.queried_fit        = kept.fits;
    kept.queried_poses      = poses;
    kept.queried_multiplier = largest_multiplier;
  }


  template <int dim>
  void
  PenaltyContact<dim>::for_each_face(
    const VectorType                                                     &u,
    const double                                                          time,
    const std::function<void(const Face &, const std::vector<Point_> &)> &face,
    const bool every) const
  {
    if (obstacle_list.empty())
      return;
    const std::vector<Pose<dim>> poses = poses_at(time);
    std::vector<Point<dim>>      x;
    std::vector<Point_>          points;
    const std::uint64_t          n_obs = obstacle_list.size();
    // Broad phase: the faces within reach of an obstacle, from a tree over
    // the faces (update_broad_phase(); on Jeffrey's muscle palpated by a
    // sphere, run explicitly, contact took 29 % of each step with every face's
    // distance computed). Then each face's own ball: the distance is 1-
    // Lipschitz, so a face whose points lie within r of their centre c has
    // every gap above g(c) - r, one distance per face and obstacle instead
    // of one per point.
    double largest_multiplier = 0;
    for (const auto &[key, state] : states)
      largest_multiplier = std::max(largest_multiplier, state.lambda);
    const auto &faces = boundary.faces();
    boundary.prepare(u);
    std::vector<unsigned int> all;
    double                    motion = 0;
    if (every)
      for (unsigned int i = 0; i < faces.size(); ++i)
        all.push_back(i);
    else
      update_broad_phase(u, poses, largest_multiplier, motion);
    const auto &kept = broad_phase;
    // With friction, the faces of the points with a state too: a friction
    // bound keeps a point that has left (keys are (face key + q) *
    // obstacles + obstacle, and the faces' keys ascend).
    if (!every && has_friction() && !states.empty())
      {
        all = kept.faces;
        for (const auto &[key, state] : states)
          {
            const auto after = std::upper_bound(kept.keys.begin(),
                                                kept.keys.end(),
                                                key / n_obs);
            if (after != kept.keys.begin())
              all.push_back(after - kept.keys.begin() - 1);
          }
        std::sort(all.begin(), all.end());
        all.erase(std::unique(all.begin(), all.end()), all.end());
      }
    const std::vector<unsigned int> &found
      = every || !all.empty() ? all : kept.faces;
    std::vector<char> near(n_obs);
    unsigned int      j = 0;
    for (const unsigned int i : found)
      {
        const Face  &f = faces[i];
        const double k = factor * modulus / f.diameter;
        if (!every)
          {
            // The fitted clearances, less the motion since: where every
            // frictionless obstacle is still out of reach, nothing of the
            // face is computed.
            while (j < kept.faces.size() && kept.faces[j] < i)
              ++j;
            const bool fitted = j < kept.faces.size() && kept.faces[j] == i;
            bool       far    = fitted;
            for (unsigned int o = 0; o < n_obs && far; ++o)
              far = obstacle_list[o].friction == 0
                    && (kept.lower[j * n_obs + o] - motion) * k
                         > largest_multiplier;
            if (far)
              continue;
          }
        boundary.deformed(f, u, x);
        points.clear();
        const auto [centre, radius] = ball_around(x);
        bool any                    = false;
        for (unsigned int o = 0; o < n_obs; ++o)
          {
            const double clearance
              = obstacle_list[o].distance(centre, poses[o]) - radius;
            near[o] = every || obstacle_list[o].friction > 0
                      || !(clearance * k > largest_multiplier);
            any = any || near[o];
          }
        if (!any)
          continue;
        for (unsigned int q = 0; q < x.size(); ++q)
          for (unsigned int o = 0; o < obstacle_list.size(); ++o)
            {
              if (!near[o])
                continue;
              // The distance first: most points touch nothing.
              const double distance = obstacle_list[o].distance(x[q], poses[o]);
              const std::uint64_t key   = (f.key + q) * n_obs + o;
              const State        *state = nullptr;
              if (!states.empty())
                if (const auto s = states.find(key); s != states.end())
                  state = &s->second;
              const double lambda = state ? state->lambda : 0.;
              // Friction's bound: mu lambda, or the penalty's mu p of the
              // last solve.
              const double bound = augmented
                                     ? obstacle_list[o].friction * lambda
                                   : state ? state->bound
                                           : 0.;
              // Active where lambda - k g >= 0; NaN gaps pass too, to be
              // seen by Newton's checks. A point with a friction bound
              // stays while it does, so that the friction potential stays
              // continuous over the solve.
              const bool active = !(lambda - k * distance < 0);
              if (!active && !every && !(bound > 0))
                continue;
              const Gap<dim>    gap    = obstacle_list[o].gap(x[q], poses[o]);
              const Point<dim> *anchor = nullptr;
              if (obstacle_list[o].friction > 0)
                {
                  if (state && state->anchored)
                    anchor = &state->anchor;
                  else if (const auto a = step_start.find(key);
                           a != step_start.end())
                    anchor = &a->second;
                }
              points.push_back({o,
                                gap,
                                k,
                                boundary.weight(f, q),
                                q,
                                key,
                                std::max(0., lambda - k * gap.distance),
                                active,
                                poses[o].local(x[q]),
                                &poses[o],
                                anchor,
                                bound,
                                state ? state->tau : Tensor<1, dim>()});
            }
        if (!points.empty())
          face(f, points);
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
    const unsigned int                   n = boundary.dofs_per_face();
    FullMatrix<double>                   K(n, n);
    Vector<double>                       r(n);
    std::vector<Tensor<1, dim>>          phi(n);
    std::vector<types::global_dof_index> dofs(n);
    auto face = [&](const Face &f, const std::vector<Point_> &points) {
      K = 0;
      r = 0;
      std::copy(boundary.dofs(f), boundary.dofs(f) + n, dofs.begin());
      for (const Point_ &p : points)
        {
          const double stiffness = p.k * p.area, force = p.pressure * p.area;
          for (unsigned int i = 0; i < n; ++i)
            phi[i] = boundary.shape(f, p.q, i);
          for (unsigned int i = 0; p.active && i < n; ++i)
            {
              const double n_i = p.gap.normal * phi[i];
              // dE/du_i = -p dg/du_i dA, dg/du_i = n . phi_i; d2E/du_i du_j
              // = (k n_i n_j - p phi_i . dn/dx phi_j) dA.
              r(i) -= force * n_i;
              if (jacobian)
                for (unsigned int j = 0; j < n; ++j)
                  K(i, j)
                    += stiffness * n_i * (p.gap.normal * phi[j])
                       - force * (phi[i] * (p.gap.normal_gradient * phi[j]));
            }
          if (!p.anchor || p.bound == 0)
            continue;
          // Coulomb friction: dE/du_i = -traction . phi_i dA.
          const Coulomb<dim> law = friction(p);
          for (unsigned int i = 0; i < n; ++i)
            {
              r(i) -= p.area * (law.traction * phi[i]);
              if (jacobian)
                for (unsigned int j = 0; j < n; ++j)
                  K(i, j) += p.area * (phi[i] * (law.tangent * phi[j]));
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
    auto   face = [&](const Face &, const std::vector<Point_> &points) {
      for (const Point_ &p : points)
        {
          sum += 0.5 * p.pressure * p.pressure / p.k * p.area;
          if (p.anchor && p.bound > 0)
            sum += p.area * friction(p).potential;
        }
    };
    for_each_face(u, time, face);
    return Utilities::MPI::sum(sum, parallel_tools::communicator());
  }


  template <int dim>
  std::vector<typename PenaltyContact<dim>::Report>
  PenaltyContact<dim>::report(const VectorType &u, const double time) const
  {
    const unsigned int  m = obstacle_list.size();
    std::vector<double> sums(m * (dim + 1), 0.), deepest(m, 0.), highest(m, 0.),
      lowest(m, std::numeric_limits<double>::infinity());
    auto face = [&](const Face &, const std::vector<Point_> &points) {
      for (const Point_ &p : points)
        {
          const unsigned int o = p.obstacle;
          // The force as add() applies it: friction wherever it has a
          // bound.
          Tensor<1, dim> traction = p.pressure * p.gap.normal;
          if (p.anchor && p.bound > 0)
            traction += friction(p).traction;
          double *s = &sums[o * (dim + 1)];
          for (unsigned int d = 0; d < dim; ++d)
            s[d] += p.area * traction[d];
          if (p.pressure > 0)
            {
              s[dim] += p.area;
              highest[o] = max_keeping_nan(highest[o], p.pressure);
              lowest[o]  = std::min(lowest[o], p.pressure);
            }
          deepest[o] = max_keeping_nan(deepest[o], -p.gap.distance);
        }
    };
    for_each_face(u, time, face);
    const MPI_Comm comm = parallel_tools::communicator();
    Utilities::MPI::sum(sums, comm, sums);
    std::vector<Report> result(m);
    for (unsigned int o = 0; o < m; ++o)
      {
        result[o].name = obstacle_list[o].name;
        for (unsigned int d = 0; d < dim; ++d)
          result[o].force[d] = sums[o * (dim + 1) + d];
        result[o].area         = sums[o * (dim + 1) + dim];
        result[o].penetration  = mpi_max_keeping_nan(deepest[o], comm);
        result[o].max_pressure = mpi_max_keeping_nan(highest[o], comm);
        const double low       = Utilities::MPI::min(lowest[o], comm);
        result[o].min_pressure = std::isfinite(low) ? low : 0.;
      }
    return result;
  }


  template <int dim>
  void
  PenaltyContact<dim>::check_start(const VectorType &u, const double time) const
  {
    const auto reports = report(u, time);
    for (unsigned int o = 0; o < reports.size(); ++o)
      if (!(reports[o].penetration <= start_tolerance))
        {
          std::ostringstream why;
          why << "obstacle '" << reports[o].name << "' starts "
              << reports[o].penetration
              << " (length units) inside the tissue, deeper than 'Contact/"
                 "Start penetration tolerance' ("
              << start_tolerance << "); move it out";
          throw InputError("Parameter '" + obstacle_list[o].slot
                           + "/Shape': " + why.str());
        }
  }


  template <int dim>
  void
  PenaltyContact<dim>::cell_fields(const VectorType &u,
                                   const double      time,
                                   Vector<float>    &pressure,
                                   Vector<float>    &gap) const
  {
    const auto &triangulation = discretization.dof_handler.get_triangulation();
    pressure.reinit(triangulation.n_active_cells());
    gap.reinit(triangulation.n_active_cells());
    if (obstacle_list.empty())
      return;
    const std::vector<Pose<dim>> poses   = poses_at(time);
    const auto                   nearest = [&](const Point<dim> &x) {
      double g = std::numeric_limits<double>::infinity();
      for (unsigned int o = 0; o < obstacle_list.size(); ++o)
        g = std::min(g, obstacle_list[o].distance(x, poses[o]));
      return g;
    };
    // Centres, moved by the mean of their vertices' displacements.
    for (const auto &cell : discretization.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          Tensor<1, dim> mean;
          for (const unsigned int v : cell->vertex_indices())
            for (unsigned int c = 0; c < dim; ++c)
              mean[c] += u(cell->vertex_dof_index(v, c));
          mean /= cell->n_vertices();
          gap[cell->active_cell_index()] = nearest(cell->center() + mean);
        }
    const std::uint64_t     faces_per_cell = GeometryInfo<dim>::faces_per_cell;
    const std::uint64_t     n_obs          = obstacle_list.size();
    std::vector<Point<dim>> x;
    for (const Face &f : boundary.faces())
      {
        const unsigned int cell
          = f.key / boundary.points_per_face() / faces_per_cell;
        boundary.deformed(f, u, x);
        const double k = factor * modulus / f.diameter;
        for (unsigned int q = 0; q < x.size(); ++q)
          for (unsigned int o = 0; o < obstacle_list.size(); ++o)
            {
              const double g      = obstacle_list[o].distance(x[q], poses[o]);
              double       lambda = 0;
              if (const auto s = states.find((f.key + q) * n_obs + o);
                  s != states.end())
                lambda = s->second.lambda;
              gap[cell]      = std::min<double>(gap[cell], g);
              pressure[cell] = std::max<double>(pressure[cell],
                                                std::max(0., lambda - k * g));
            }
      }
  }


  template class PenaltyContact<1>;
  template class PenaltyContact<2>;
  template class PenaltyContact<3>;
} // namespace tissuefem::contact
