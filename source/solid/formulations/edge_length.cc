#include <tissuefem/solid/edge_length_element.h>
#include <tissuefem/solid/formulations/edge_length.h>

namespace tissuefem::solid::formulations
{
  namespace
  {
    /// The cell's reference vertices and barycentric gradients.
    template <int dim>
    struct EdgeScratch : public Scratch
    {
      explicit EdgeScratch(const unsigned int n_scalar)
          : vertices(n_scalar)
          , gradients(n_scalar)
      {
      }
      std::unique_ptr<Scratch>
      clone() const override
      {
        return std::make_unique<EdgeScratch>(*this);
      }
      std::vector<Point<dim>>     vertices;
      std::vector<Tensor<1, dim>> gradients;
    };
  } // namespace


  template <int dim>
  void
  EdgeLength<dim>::check(const Discretization<dim>         &discretization,
                         const materials::MaterialSet<dim> &materials) const
  {
    for (const auto &[name, model] : materials.models())
      require(model->has_edge_length_form(),
              "Materials/Formulation",
              "'edge length' is not available for model '" + name
                + "' (it is not written in C = F^T F)");
    require(discretization.simplex && discretization.fe->degree == 1,
            "Materials/Formulation",
            "'edge length' needs linear simplices (Geometry/Cell type = "
            "simplex or a simplex mesh file, Polynomial degree = 1)");
  }


  template <int dim>
  std::unique_ptr<Scratch>
  EdgeLength<dim>::make_scratch(const Context<dim> &context) const
  {
    return std::make_unique<EdgeScratch<dim>>(context.cache.n_scalar);
  }


  template <int dim>
  bool
  EdgeLength<dim>::cell_terms(const Context<dim> &context,
                              CellTerms<dim>     &cell) const
  {
    deformation_gradients(context.cache, cell);
    check_inversion(cell);
    return false;
  }


  template <int dim>
  void
  EdgeLength<dim>::add_cell_rows(const Context<dim> &context,
                                 CellTerms<dim>     &cell) const
  {
    const auto   &cache  = context.cache;
    const double *JxW    = cache.JxW(cell.c);
    double        volume = 0;
    for (unsigned int q = 0; q < cache.n_q; ++q)
      volume += JxW[q];
    auto       &s          = static_cast<EdgeScratch<dim> &>(*cell.own);
    const auto &cache_cell = cache.cells()[cell.c];
    for (unsigned int k = 0; k < cache.n_scalar; ++k)
      {
        s.vertices[k]  = cache_cell->vertex(k);
        s.gradients[k] = cache.gradient(cell.c, 0, k);
      }
    add_edge_length_element(s.vertices,
                            s.gradients,
                            volume,
                            cell.U,
                            cache.local_index,
                            *cell.material,
                            context.fibres.at(cell.index, 0),
                            *cell.rhs,
                            cell.jacobian ? cell.matrix : nullptr);
  }


  template class EdgeLength<1>;
  template class EdgeLength<2>;
  template class EdgeLength<3>;

  TISSUEFEM_REGISTER_FORMULATION(
    EdgeLength,
    "edge length",
    "Jeffrey's form (eqs 19-31), the element energy written through the "
    "squared edge lengths of linear simplices (P1 triangles/tetrahedra "
    "only, models written in C = F^T F: St Venant-Kirchhoff and the "
    "transversely isotropic one; the fibre direction is taken as the "
    "normalized cell mean, one per element).")
} // namespace tissuefem::solid::formulations
