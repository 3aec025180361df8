#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/tria.h>

#include <memory>

namespace tissuefem::solid
{
  using namespace dealii;

  /// The 'Finite element' subsection.
  struct FiniteElementParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    unsigned int degree;
    /// Gauss points per direction; 0 means degree + 1.
    unsigned int quadrature_points;
  };

  /**
   * The element, mapping and quadrature rules matching a triangulation's
   * cell type: FE_Q (Q_k) on quadrilaterals/hexahedra, FE_SimplexP (P_k) on
   * triangles/tetrahedra, repeated @p n_components times in an FESystem.
   */
  template <int dim>
  class Discretization
  {
  public:
    Discretization(const Triangulation<dim>      &triangulation,
                   const FiniteElementParameters &parameters,
                   const unsigned int             n_components);

    std::unique_ptr<FiniteElement<dim>> fe;
    std::unique_ptr<Mapping<dim>>       mapping;
    Quadrature<dim>                     cell_quadrature;
    Quadrature<dim - 1>                 face_quadrature;
    DoFHandler<dim>                     dof_handler;
    bool                                simplex;
  };
} // namespace tissuefem::solid
