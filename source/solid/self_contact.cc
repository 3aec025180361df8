#include <tissuefem/solid/self_contact.h>
#include <tissuefem/solid/self_overlap.h>

#include <algorithm>
#include <vector>

namespace tissuefem::solid
{
  namespace
  {
    /// The overlap density of self_contact.h: how many coverings of a point
    /// with winding number @p w are too many or negative.
    double
    excess_coverings(const double w)
    {
      return std::max(w - 1, 0.) + std::max(-w, 0.);
    }
  } // namespace


  template <int dim>
  void
  add_overlap_force(const Discretization<dim>       &discretization,
                    const VectorType                &u,
                    const double                     pressure,
                    const AffineConstraints<double> &constraints,
                    VectorType                      &force)
  {
    const auto               &dof_handler = discretization.dof_handler;
    const BoundaryFacets<dim> facets = gather_boundary_facets(dof_handler, u);
    unsigned int              k      = facets.first_local;
    Vector<double>            local(dim * dim);
    std::vector<types::global_dof_index> dofs(dim * dim);
    for_each_boundary_piece(
      dof_handler, [&](const auto &face, const auto &piece) {
        std::array<Point<dim>, dim> x;
        Point<dim>                  centre;
        for (unsigned int i = 0; i < dim; ++i)
          {
            for (unsigned int c = 0; c < dim; ++c)
              x[i][c] = facets.coordinates[(k * dim + i) * dim + c];
            centre += x[i] / dim;
          }
        const double w = winding_number(centre, facets.coordinates, k);
        ++k;
        const double change
          = excess_coverings(w + 0.5) - excess_coverings(w - 0.5);
        if (change == 0)
          return;
        // f = -p_c dV_o/dx: the area vector shared by the facet's vertices.
        const Tensor<1, dim> share
          = -pressure * change * oriented_area<dim>(x) / dim;
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int c = 0; c < dim; ++c)
            {
              local[i * dim + c] = share[c];
              dofs[i * dim + c]  = face->vertex_dof_index(piece[i], c);
            }
        constraints.distribute_local_to_global(local, dofs, force);
      });
    force.compress(VectorOperation::add);
  }


#define TISSUEFEM_INSTANTIATE(dim)                                   \
  template void add_overlap_force(const Discretization<dim> &,       \
                                  const VectorType &,                \
                                  const double,                      \
                                  const AffineConstraints<double> &, \
                                  VectorType &);
  TISSUEFEM_INSTANTIATE(1)
  TISSUEFEM_INSTANTIATE(2)
  TISSUEFEM_INSTANTIATE(3)
#undef TISSUEFEM_INSTANTIATE
} // namespace tissuefem::solid
