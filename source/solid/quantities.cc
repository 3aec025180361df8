#include <deal.II/lac/lapack_full_matrix.h>

#include <tissuefem/base/nan_aware.h>
#include <tissuefem/solid/deformation_gradients.h>
#include <tissuefem/solid/quantities.h>

#include <limits>

namespace tissuefem::solid
{


  template <int dim>
  void
  cell_fields(const Discretization<dim>            &discretization,
              const materials::MaterialSet<dim>    &materials,
              const FibreField<dim>                &fibres,
              const formulations::Deformation<dim> *deformation,
              const VectorType                     &u,
              Vector<float>                        &jacobian,
              Vector<float>                        &von_mises)
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
        const auto &material = materials.material(cell->material_id());
        if (J <= 0 && !material.admits_inversion())
          return;
        Tensor<2, dim> P
          = material.stress(F, fibres.at(cell->active_cell_index(), q));
        // The formulation's own pressure, where it has one.
        double psi = 0;
        if (deformation)
          deformation->add_own_terms(cell, F, psi, &P);
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
      },
      deformation);
  }


  template <int dim>
  double
  min_jacobian(const Discretization<dim> &discretization, const VectorType &u)
  {
    double smallest = std::numeric_limits<double>::max();
    for_each_deformation_gradient(
      discretization,
      u,
      [&](const auto &, unsigned int, const Tensor<2, dim> &F, double) {
        smallest = std::min(smallest, determinant(F));
      });
    return Utilities::MPI::min(smallest, parallel_tools::communicator());
  }


  template <int dim>
  double
  distance_from_rest_shape(const Discretization<dim> &discretization,
                           const VectorType          &u)
  {
    // Reference and deformed positions of the vertices whose dofs this
    // process owns (each vertex counted once over all processes).
    const auto &dof_handler = discretization.dof_handler;
    std::map<unsigned int, std::pair<Point<dim>, Point<dim>>> vertices;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() || cell->is_ghost())
        for (const unsigned int v : cell->vertex_indices())
          if (discretization.locally_owned.is_element(
                cell->vertex_dof_index(v, 0)))
            {
              vertices[cell->vertex_index(v)]
                = {cell->vertex(v), deformed_vertex<dim>(cell, v, u)};
            }
    const MPI_Comm comm = parallel_tools::communicator();
    const double   n_vertices
      = Utilities::MPI::sum(double(vertices.size()), comm);
    Tensor<1, dim> X_mean, x_mean;
    for (const auto &[index, pair] : vertices)
      {
        X_mean += pair.first / n_vertices;
        x_mean += pair.second / n_vertices;
      }
    X_mean = Utilities::MPI::sum(X_mean, comm);
    x_mean = Utilities::MPI::sum(x_mean, comm);
    // R maximizes sum (x - x_mean) . R (X - X_mean): R = U diag(1, .., det)
    // V^T from the SVD M = U S V^T of M = sum (x - x_mean) (x) (X - X_mean).
    Tensor<2, dim> covariance;
    for (const auto &[index, pair] : vertices)
      covariance += outer_product(Tensor<1, dim>(pair.second) - x_mean,
                                  Tensor<1, dim>(pair.first) - X_mean);
    covariance = Utilities::MPI::sum(covariance, comm);
    LAPACKFullMatrix<double> M(dim, dim);
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        M(i, j) = covariance[i][j];
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
        = max_keeping_nan(distance,
                          (x_mean + R * (Tensor<1, dim>(pair.first) - X_mean)
                           - Tensor<1, dim>(pair.second))
                            .norm());
    return mpi_max_keeping_nan(distance, comm);
  }

#define TISSUEFEM_INSTANTIATE(dim)                                           \
  template void   cell_fields<dim>(const Discretization<dim> &,              \
                                 const materials::MaterialSet<dim> &,      \
                                 const FibreField<dim> &,                  \
                                 const formulations::Deformation<dim> *,   \
                                 const VectorType &,                       \
                                 Vector<float> &,                          \
                                 Vector<float> &);                         \
  template double min_jacobian<dim>(const Discretization<dim> &,             \
                                    const VectorType &);                     \
  template double distance_from_rest_shape<dim>(const Discretization<dim> &, \
                                                const VectorType &);
  TISSUEFEM_INSTANTIATE(1)
  TISSUEFEM_INSTANTIATE(2)
  TISSUEFEM_INSTANTIATE(3)
#undef TISSUEFEM_INSTANTIATE
} // namespace tissuefem::solid
