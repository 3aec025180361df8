#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <tuple>
#include <vector>

#include <tissuefem/base/parallel.h>
#include <tissuefem/boundary/boundary_conditions.h>

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
    /// Whether linear simplices may use the lean element kernel.
    bool lean_kernel = true;
    /// 'Mass' is 'lumped': the implicit integrators' mass is the row-sum
    /// lumped one.
    bool lumped_mass = false;
  };

  /**
   * The element, mapping and quadrature rules matching a triangulation's
   * cell type: FE_Q (Q_k) on quadrilaterals/hexahedra, FE_SimplexP (P_k) on
   * triangles/tetrahedra, repeated @p n_components times in an FESystem;
   * and, for the current mesh, the degrees of freedom, which of them this
   * process owns and sees, and the homogeneous constraints (hanging nodes,
   * Dirichlet components) that Newton updates obey. distribute() is called
   * again whenever the mesh changes.
   */
  /// (dof, vertex, component) of every displacement dof at the listed
  /// triangulation vertices that lies in @p relevant, sorted.
  template <int dim>
  std::vector<std::tuple<types::global_dof_index, unsigned int, unsigned int>>
  held_vertex_dofs(const DoFHandler<dim>           &dof_handler,
                   const std::vector<unsigned int> &vertices,
                   const IndexSet                  &relevant);

  template <int dim>
  class Discretization
  {
  public:
    Discretization(const Triangulation<dim>      &triangulation,
                   const FiniteElementParameters &parameters,
                   const unsigned int             n_components);

    /// Numbers the degrees of freedom of the current mesh and builds the
    /// constraints: hanging nodes, and zero for every component that
    /// @p boundary_conditions prescribes (none if it is null), and every
    /// component of the @p held_vertices (a tool's grasp; none if null).
    void
    distribute(const boundary::BoundaryConditions<dim> *boundary_conditions,
               const std::vector<unsigned int> *held_vertices = nullptr);

    /// A distributed vector of the degrees of freedom this process owns;
    /// with @p ghosted, read-only copies of those it sees as well.
    void
    initialize_vector(VectorType &v, const bool ghosted = false) const;

    /// A vector into which cell contributions to any row, also rows owned
    /// elsewhere, may be added (call compress(VectorOperation::add)
    /// afterwards).
    void
    initialize_assembly_vector(VectorType &v) const;

    /// The rigid-body modes of the reference configuration (dim
    /// translations, then dim (dim - 1)/2 rotations), distributed like the
    /// unknowns: the near-null space of elasticity for algebraic multigrid.
    std::vector<VectorType>
    rigid_body_modes() const;

    types::global_dof_index
    n_dofs() const
    {
      return dof_handler.n_dofs();
    }

    std::unique_ptr<FiniteElement<dim>> fe;
    std::unique_ptr<Mapping<dim>>       mapping;
    Quadrature<dim>                     cell_quadrature;
    Quadrature<dim - 1>                 face_quadrature;
    DoFHandler<dim>                     dof_handler;
    bool                                simplex;
    /// 'Finite element/Element kernel' is 'automatic'.
    bool lean_kernel = true;
    /// 'Finite element/Mass' is 'lumped': inertia everywhere (implicit
    /// residuals and Jacobians, energies, reactions) with the row-sum
    /// lumped mass instead of the consistent one.
    bool lumped_mass = false;

    IndexSet                  locally_owned;
    IndexSet                  locally_relevant;
    AffineConstraints<double> constraints;
    /// Hanging-node constraints only (for interpolating data).
    AffineConstraints<double> hanging_node_constraints;
    /// Whether any process has hanging nodes (the same on every process).
    bool has_hanging_nodes = false;
  };
} // namespace tissuefem::solid
