#include <tissuefem/materials/tangent_projection.h>
#include <tissuefem/solid/formulations/displacement.h>

namespace tissuefem::solid::formulations
{
  template <int dim>
  void
  Displacement<dim>::check(const Discretization<dim> &,
                           const materials::MaterialSet<dim> &) const
  {
  }


  template <int dim>
  bool
  Displacement<dim>::cell_terms(const Context<dim> &context,
                                CellTerms<dim>     &cell) const
  {
    const auto &cache = context.cache;
    deformation_gradients(cache, cell);
    check_inversion(cell);
    if (cell.inverted_det <= 0)
      return true;
    const auto method  = context.materials.tangent_method();
    const bool project = context.materials.project_tangent();
    for (unsigned int q = 0; q < cache.n_q; ++q)
      {
        const Tensor<1, dim> &a = context.fibres.at(cell.index, q);
        if (!cell.jacobian)
          cell.P[q] = cell.material->stress(cell.F[q], a);
        else
          {
            cell.material->stress_and_tangent(
              cell.F[q], a, cell.P[q], cell.A[q], method);
            if (project)
              materials::project_to_positive_definite(cell.A[q]);
          }
      }
    return true;
  }


  template class Displacement<1>;
  template class Displacement<2>;
  template class Displacement<3>;

  TISSUEFEM_REGISTER_FORMULATION(
    Displacement,
    "displacement",
    "P(F) at the quadrature points from the displacement's gradient; any "
    "element (locks where the material is nearly incompressible on linear "
    "simplices and Q1).");
} // namespace tissuefem::solid::formulations
