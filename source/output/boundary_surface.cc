#include <deal.II/base/mpi.h>

#include <tissuefem/output/boundary_surface.h>

#include <limits>

namespace tissuefem::output
{
  namespace
  {
    constexpr unsigned int none = std::numeric_limits<unsigned int>::max();

    /// The polygon's corners in cyclic order: deal.II numbers a
    /// quadrilateral's vertices lexicographically (0 1 / 2 3), a
    /// triangle's cyclically.
    std::vector<unsigned int>
    cyclic(const std::vector<unsigned int> &corners)
    {
      if (corners.size() == 4)
        return {corners[0], corners[1], corners[3], corners[2]};
      return corners;
    }
  } // namespace


  template <int dim>
  BoundarySurface<dim>::BoundarySurface(const Triangulation<dim> &triangulation)
      : surface_index(triangulation.n_vertices(), none)
  {
    const auto &points = triangulation.get_vertices();
    auto        index  = [&](const unsigned int v) {
      if (surface_index[v] == none)
        {
          surface_index[v] = vertices.size();
          vertices.push_back(v);
          for (unsigned int d = 0; d < 3; ++d)
            positions.push_back(d < dim ? float(points[v][d]) : 0.f);
        }
      return surface_index[v];
    };
    // Adds the fan of triangles of a polygon, each turned so that its
    // normal points along @p outward.
    auto add_polygon = [&](const std::vector<unsigned int> &corners,
                           const Tensor<1, 3>              &outward) {
      for (unsigned int k = 1; k + 1 < corners.size(); ++k)
        {
          unsigned int a = corners[0], b = corners[k], c = corners[k + 1];
          Tensor<1, 3> p[3];
          for (unsigned int d = 0; d < dim; ++d)
            {
              p[0][d] = points[a][d];
              p[1][d] = points[b][d];
              p[2][d] = points[c][d];
            }
          if (cross_product_3d(p[1] - p[0], p[2] - p[0]) * outward < 0)
            std::swap(b, c);
          for (const unsigned int v : {a, b, c})
            triangles.push_back(index(v));
        }
    };

    for (const auto &cell : triangulation.active_cell_iterators())
      if constexpr (dim == 1)
        break; // a 1D body has no surface to draw
      else if constexpr (dim == 2)
        {
          std::vector<unsigned int> corners;
          for (const unsigned int v : cell->vertex_indices())
            corners.push_back(cell->vertex_index(v));
          add_polygon(cyclic(corners), Tensor<1, 3>({0., 0., 1.}));
        }
      else
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              const auto                face = cell->face(f);
              std::vector<unsigned int> corners;
              for (const unsigned int v : face->vertex_indices())
                corners.push_back(face->vertex_index(v));
              Tensor<1, 3> outward;
              const auto   from = face->center() - cell->center();
              for (unsigned int d = 0; d < dim; ++d)
                outward[d] = from[d];
              add_polygon(cyclic(corners), outward);
            }
  }


  template <int dim>
  void
  BoundarySurface<dim>::gather(
    const DoFHandler<dim>            &dof_handler,
    const VectorType                 &u,
    const std::vector<Vector<float>> &cell_values,
    std::vector<float>               &displacement,
    std::vector<std::vector<float>>  &vertex_values) const
  {
    const unsigned int n = vertices.size(), fields = cell_values.size();
    // Per surface vertex: dim displacements, then each field's sum, then
    // how many cells added to them (a vertex's displacement is the same
    // from every cell around it, so its sum is divided by the count too).
    const unsigned int                   stride = dim + fields + 1;
    std::vector<double>                  sums(n * stride, 0.);
    const auto                          &fe = dof_handler.get_fe();
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(dofs);
          for (const unsigned int v : cell->vertex_indices())
            {
              const unsigned int s = surface_index[cell->vertex_index(v)];
              if (s == none)
                continue;
              double *row = &sums[s * stride];
              for (unsigned int k = 0; k < fe.n_dofs_per_vertex(); ++k)
                {
                  const unsigned int i = v * fe.n_dofs_per_vertex() + k;
                  row[fe.system_to_component_index(i).first] += u(dofs[i]);
                }
              for (unsigned int f = 0; f < fields; ++f)
                row[dim + f] += cell_values[f][cell->active_cell_index()];
              row[stride - 1] += 1;
            }
        }
    Utilities::MPI::sum(sums, dof_handler.get_communicator(), sums);

    displacement.assign(3 * n, 0.f);
    vertex_values.assign(fields, std::vector<float>(n, 0.f));
    for (unsigned int s = 0; s < n; ++s)
      {
        const double *row   = &sums[s * stride];
        const double  count = std::max(row[stride - 1], 1.);
        for (unsigned int d = 0; d < dim; ++d)
          displacement[3 * s + d] = row[d] / count;
        for (unsigned int f = 0; f < fields; ++f)
          vertex_values[f][s] = row[dim + f] / count;
      }
  }

  template class BoundarySurface<1>;
  template class BoundarySurface<2>;
  template class BoundarySurface<3>;
} // namespace tissuefem::output
