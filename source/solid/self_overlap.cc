#include <deal.II/base/mpi.h>

#include <tissuefem/solid/deformation_gradients.h>
#include <tissuefem/solid/self_overlap.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace tissuefem::solid
{
  template <int dim>
  BoundaryFacets<dim>
  gather_boundary_facets(const DoFHandler<dim> &dof_handler,
                         const VectorType      &u)
  {
    BoundaryFacets<dim> result;
    if (dim == 1)
      return result;
    std::vector<double> local;
    for_each_boundary_piece(dof_handler,
                            [&](const auto &face, const auto &piece) {
                              for (const unsigned int v : piece)
                                {
                                  const Point<dim> x
                                    = deformed_vertex<dim>(face, v, u);
                                  for (unsigned int c = 0; c < dim; ++c)
                                    local.push_back(x[c]);
                                }
                            });
    const auto parts
      = Utilities::MPI::all_gather(parallel_tools::communicator(), local);
    const unsigned int rank
      = Utilities::MPI::this_mpi_process(parallel_tools::communicator());
    for (unsigned int p = 0; p < parts.size(); ++p)
      {
        if (p == rank)
          result.first_local = result.coordinates.size() / (dim * dim);
        result.coordinates.insert(result.coordinates.end(),
                                  parts[p].begin(),
                                  parts[p].end());
      }
    return result;
  }


  double
  winding_number(const Point<2>            &y,
                 const std::vector<double> &facets,
                 const unsigned int         skip)
  {
    double angle = 0;
    for (unsigned int i = 0, k = 0; i + 3 < facets.size(); i += 4, ++k)
      if (k != skip)
        {
          const double ax = facets[i] - y[0], ay = facets[i + 1] - y[1];
          const double bx = facets[i + 2] - y[0], by = facets[i + 3] - y[1];
          angle += std::atan2(ax * by - ay * bx, ax * bx + ay * by);
        }
    return angle / (2 * M_PI);
  }


  double
  winding_number(const Point<3>            &y,
                 const std::vector<double> &facets,
                 const unsigned int         skip)
  {
    // The solid angle of a triangle (Van Oosterom and Strackee 1983).
    double solid_angle = 0;
    for (unsigned int i = 0, k = 0; i + 8 < facets.size(); i += 9, ++k)
      if (k != skip)
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
  winding_number(const Point<1> &, const std::vector<double> &, unsigned int)
  {
    return 1;
  }


  template <int dim>
  double
  tangled_volume_fraction(const Discretization<dim> &discretization,
                          const VectorType          &u)
  {
    const auto               &dof_handler = discretization.dof_handler;
    const MPI_Comm            comm        = parallel_tools::communicator();
    const std::vector<double> facets
      = gather_boundary_facets(dof_handler, u).coordinates;

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


#define TISSUEFEM_INSTANTIATE(dim)                                             \
  template BoundaryFacets<dim> gather_boundary_facets(const DoFHandler<dim> &, \
                                                      const VectorType &);
  TISSUEFEM_INSTANTIATE(1)
  TISSUEFEM_INSTANTIATE(2)
  TISSUEFEM_INSTANTIATE(3)
#undef TISSUEFEM_INSTANTIATE

  template double
  tangled_volume_fraction<1>(const Discretization<1> &, const VectorType &);
  template double
  tangled_volume_fraction<2>(const Discretization<2> &, const VectorType &);
  template double
  tangled_volume_fraction<3>(const Discretization<3> &, const VectorType &);
} // namespace tissuefem::solid
