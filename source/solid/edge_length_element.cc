#include <tissuefem/solid/edge_length_element.h>

namespace tissuefem::solid
{
  template <int dim>
  void
  add_edge_length_element(const std::vector<Point<dim>>     &vertices,
                          const std::vector<Tensor<1, dim>> &gradients,
                          const double                       volume,
                          const std::vector<Tensor<1, dim>> &displacement,
                          const std::vector<unsigned int>   &local_index,
                          const materials::Interface<dim>   &material,
                          const Tensor<1, dim>              &fibre,
                          Vector<double>                    &cell_rhs,
                          FullMatrix<double>                *cell_matrix)
  {
    // The material's element works with deformed node positions Q, indexed
    // node * dim + component, like local_index.
    std::vector<Tensor<1, dim>> Q(dim + 1);
    for (unsigned int k = 0; k <= dim; ++k)
      Q[k] = vertices[k] + displacement[k];
    double              energy;
    std::vector<double> forces, stiffness;
    material.edge_length_element(gradients,
                                 volume,
                                 Q,
                                 fibre,
                                 energy,
                                 forces,
                                 cell_matrix ? &stiffness : nullptr);
    const unsigned int n = (dim + 1) * dim;
    for (unsigned int a = 0; a < n; ++a)
      {
        const unsigned int i = local_index[a];
        cell_rhs[i] += forces[a];
        if (cell_matrix)
          for (unsigned int b = 0; b < n; ++b)
            {
              const unsigned int j = local_index[b];
              if (i <= j)
                (*cell_matrix)(i, j) += stiffness[a * n + b];
            }
      }
  }

  template void
  add_edge_length_element<1>(const std::vector<Point<1>> &,
                             const std::vector<Tensor<1, 1>> &,
                             double,
                             const std::vector<Tensor<1, 1>> &,
                             const std::vector<unsigned int> &,
                             const materials::Interface<1> &,
                             const Tensor<1, 1> &,
                             Vector<double> &,
                             FullMatrix<double> *);
  template void
  add_edge_length_element<2>(const std::vector<Point<2>> &,
                             const std::vector<Tensor<1, 2>> &,
                             double,
                             const std::vector<Tensor<1, 2>> &,
                             const std::vector<unsigned int> &,
                             const materials::Interface<2> &,
                             const Tensor<1, 2> &,
                             Vector<double> &,
                             FullMatrix<double> *);
  template void
  add_edge_length_element<3>(const std::vector<Point<3>> &,
                             const std::vector<Tensor<1, 3>> &,
                             double,
                             const std::vector<Tensor<1, 3>> &,
                             const std::vector<unsigned int> &,
                             const materials::Interface<3> &,
                             const Tensor<1, 3> &,
                             Vector<double> &,
                             FullMatrix<double> *);
} // namespace tissuefem::solid
