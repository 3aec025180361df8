#include <deal.II/base/mpi.h>

#include <tissuefem/solid/deformation_gradients.h>
#include <tissuefem/solid/self_overlap.h>

#include <cmath>
#include <vector>

namespace tissuefem::solid
{
  namespace
  {
    /// Appends the boundary facets of the locally owned cells, deformed
    /// and oriented so that their reference normal points out of the body
    /// (2D: segments, 4 numbers; 3D: triangles, 9 numbers).
    template <int dim>
    void
    add_boundary_facets(const DoFHandler<dim> &dof_handler,
                        const VectorType      &u,
                        std::vector<double>   &facets)
    {
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned() && cell->at_boundary())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary())
              {
                // Triangles of the face (a quadrilateral's vertices are
                // numbered lexicographically: 0 1 3 and 0 3 2 go round).
                std::vector<std::vector<unsigned int>> pieces;
                if (dim == 2)
                  pieces = {{0, 1}};
                else if (face->n_vertices() == 3)
                  pieces = {{0, 1, 2}};
                else
                  pieces = {{0, 1, 3}, {0, 3, 2}};
                const Tensor<1, dim> out = face->center() - cell->center();
                for (auto &piece : pieces)
                  {
                    // Orient by the reference normal.
                    std::vector<Point<dim>> X;
                    for (const unsigned int v : piece)
                      X.push_back(face->vertex(v));
                    Tensor<1, dim> normal;
                    if constexpr (dim == 2)
                      {
                        normal[0] = X[1][1] - X[0][1];
                        normal[1] = X[0][0] - X[1][0];
                      }
                    if constexpr (dim == 3)
                      normal = cross_product_3d(X[1] - X[0], X[2] - X[0]);
                    if (normal * out < 0)
                      std::swap(piece[0], piece[1]);
                    for (const unsigned int v : piece)
                      {
                        const Point<dim> x = deformed_vertex<dim>(face, v, u);
                        for (unsigned int c = 0; c < dim; ++c)
                          facets.push_back(x[c]);
                      }
                  }
              }
    }


    /// The winding number of the closed boundary @p facets around @p y.
    double
    winding_number(const Point<2> &y, const std::vector<double> &facets)
    {
      double angle = 0;
      for (unsigned int i = 0; i + 3 < facets.size(); i += 4)
        {
          const double ax = facets[i] - y[0], ay = facets[i + 1] - y[1];
          const double bx = facets[i + 2] - y[0], by = facets[i + 3] - y[1];
          angle += std::atan2(ax * by - ay * bx, ax * bx + ay * by);
        }
      return angle / (2 * M_PI);
    }

    double
    winding_number(const Point<3> &y, const std::vector<double> &facets)
    {
      // The solid angle of a triangle (Van Oosterom and Strackee 1983).
      double solid_angle = 0;
      for (unsigned int i = 0; i + 8 < facets.size(); i += 9)
        {
          Tensor<1, 3> a, b, c;
          for (unsigned int d = 0; d < 3; ++d)
            {
              a[d] = facets[i + d] - y[d];
              b[d] = facets[i + 3 + d] - y[d];
              c[d] = facets[i + 6 + d] - y[d];
            }
          const double la = a.norm(), lb = b.norm(), lc = c.norm();
          const double numerator = a * cross_product_3d(b, c);
          const double denominator
            = la * lb * lc + (a * b) * lc + (a * c) * lb + (b * c) * la;
          solid_angle += 2 * std::atan2(numerator, denominator);
        }
      return solid_angle / (4 * M_PI);
    }

    double
    winding_number(const Point<1> &, const std::vector<double> &)
    {
      return 1;
    }
  } // namespace


  template <int dim>
  double
  tangled_volume_fraction(const Discretization<dim> &discretization,
                          const VectorType          &u)
  {
    const auto         &dof_handler = discretization.dof_handler;
    const MPI_Comm      comm        = parallel_tools::communicator();
    std::vector<double> local_facets, facets;
    if (dim > 1)
      add_boundary_facets(dof_handler, u, local_facets);
    for (const auto &part : Utilities::MPI::all_gather(comm, local_facets))
      facets.insert(facets.end(), part.begin(), part.end());

    // Per cell: its smallest det F and its volume.
    const unsigned int n_cells
      = dof_handler.get_triangulation().n_active_cells();
    std::vector<double> smallest(n_cells, 1), cell_volume(n_cells, 0);
    for_each_deformation_gradient(
      discretization,
      u,
      [&](const auto &cell, unsigned int, const Tensor<2, dim> &F, double JxW) {
        const unsigned int i = cell->active_cell_index();
        smallest[i]          = std::min(smallest[i], determinant(F));
        cell_volume[i] += JxW;
      });
    double tangled = 0, volume = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const unsigned int i = cell->active_cell_index();
          Point<dim>         centre;
          for (const unsigned int v : cell->vertex_indices())
            centre += deformed_vertex<dim>(cell, v, u) / cell->n_vertices();
          volume += cell_volume[i];
          if (smallest[i] <= 0
              || std::abs(winding_number(centre, facets) - 1) > 0.5)
            tangled += cell_volume[i];
        }
    return Utilities::MPI::sum(tangled, comm)
           / Utilities::MPI::sum(volume, comm);
  }


  template double
  tangled_volume_fraction<1>(const Discretization<1> &, const VectorType &);
  template double
  tangled_volume_fraction<2>(const Discretization<2> &, const VectorType &);
  template double
  tangled_volume_fraction<3>(const Discretization<3> &, const VectorType &);
} // namespace tissuefem::solid
