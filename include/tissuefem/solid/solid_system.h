#pragma once

#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/boundary/boundary_conditions.h>
#include <tissuefem/materials/material_set.h>
#include <tissuefem/solid/discretization.h>

namespace tissuefem::solid
{
  /// Thrown when an element inverts (det F <= 0) in a model whose energy is
  /// undefined there; the time stepper may retry with a smaller step.
  class InvertedElementError : public SolverError
  {
  public:
    using SolverError::SolverError;
  };

  /**
   * The discrete equations of a hyperelastic solid in the reference
   * configuration. For a displacement vector u it assembles the residual
   *
   *   R(u) = c M (u - u_tilde) + f_int(u) - f_ext(t),
   *   f_int_a = int P(F) : grad N_a dV,  f_ext_a = int (rho_0 g + b) N_a dV
   *                                              + int h N_a dA,
   *
   * and, on request, its Jacobian c M + df_int/du, where M is the consistent
   * mass matrix. c = 1/dt^2 with u_tilde = u_n + dt v_n is backward Euler
   * (the problem session's eq 6 divided by dt^2); c = 0 is quasistatics.
   * Rows and columns of Dirichlet degrees of freedom are eliminated
   * (homogeneous constraints on the Newton update).
   */
  template <int dim>
  class SolidSystem
  {
  public:
    SolidSystem(const Discretization<dim>         &discretization,
                const materials::MaterialSet<dim> &materials,
                boundary::BoundaryConditions<dim> &boundary_conditions);

    void
    assemble(const Vector<double> &u,
             const Vector<double> &u_tilde,
             const double          mass_coefficient,
             const double          time,
             Vector<double>       &residual,
             const bool            with_tangent);

    /**
     * The force the supports apply to the body through each boundary in
     * @p boundary_ids: the sum, over the degrees of freedom on that
     * boundary, of the unconstrained residual c M (u - u_tilde) + f_int(u)
     * - f_ext (force units; a tool holding that boundary feels the
     * opposite). With the arguments of the step just solved.
     */
    std::vector<Tensor<1, dim>>
    reaction_forces(const Vector<double>                  &u,
                    const Vector<double>                  &u_tilde,
                    const double                           mass_coefficient,
                    const double                           time,
                    const std::vector<types::boundary_id> &boundary_ids);

    /// The Jacobian of the last assemble() call with @p with_tangent.
    SparseMatrix<double> &
    tangent()
    {
      return tangent_matrix;
    }

    /// Sets the Dirichlet degrees of freedom of @p u to their values at
    /// @p time.
    void
    apply_dirichlet_values(const double time, Vector<double> &u);

    /// Interpolates the initial displacement and velocity expressions.
    void
    initial_state(Vector<double> &u, Vector<double> &v) const;

    /**
     * Per-cell averages over quadrature points of J = det F and of the von
     * Mises equivalent of the Cauchy stress sigma = P F^T / J (computed from
     * the dim x dim stress: sqrt(3/2 dev(sigma) : dev(sigma)); in 1D |sigma|;
     * in 2D the out-of-plane stress is not included).
     */
    void
    cell_fields(const Vector<double> &u,
                Vector<float>        &jacobian,
                Vector<float>        &von_mises) const;

    /// Total elastic energy int Psi(F) dV (energy units).
    double
    elastic_energy(const Vector<double> &u) const;

    /**
     * How far the deformed body is from its rest shape up to a rigid
     * motion: the largest distance, over the mesh vertices, between
     * X + u(X) and the best-fitting rotation and translation of X (the
     * rotation from the SVD of the covariance, with det R = +1 so mirror
     * images count as far). Length units.
     */
    double
    distance_from_rest_shape(const Vector<double> &u) const;

    /// The smallest J = det F over all quadrature points.
    double
    min_jacobian(const Vector<double> &u) const;

    /// The cell averages of the unit fibre direction, one vector per
    /// component (empty if no material uses fibres).
    std::vector<Vector<float>>
    cell_fibre_directions() const;

    unsigned int
    n_dofs() const
    {
      return discretization.dof_handler.n_dofs();
    }

    const Discretization<dim> &
    get_discretization() const
    {
      return discretization;
    }

  private:
    const Discretization<dim>         &discretization;
    const materials::MaterialSet<dim> &materials;
    boundary::BoundaryConditions<dim> &boundary_conditions;
    AffineConstraints<double>          constraints;
    /// Empty: distributes into every row (for reaction forces).
    AffineConstraints<double> no_constraints;
    SparsityPattern           sparsity;
    SparseMatrix<double>      tangent_matrix;
    bool                      body_force_present;
    /// The unit fibre direction at quadrature point q of cell c, stored at
    /// c * n_q + q; empty when no material uses fibres.
    std::vector<Tensor<1, dim>> fibres;

    const Tensor<1, dim> &
    fibre(const unsigned int cell_index, const unsigned int q) const;

    /// Adds the edge-length element's forces and stiffness (Jeffrey eqs
    /// 19-31) to the cell residual and matrix.
    void
    add_edge_length_element(
      const typename DoFHandler<dim>::active_cell_iterator &cell,
      const FEValues<dim>                                  &fe_values,
      const std::vector<double>                            &u_cell,
      const materials::Interface<dim>                      &material,
      Vector<double>                                       &cell_rhs,
      FullMatrix<double>                                   *cell_matrix) const;

    void
    assemble_with(const AffineConstraints<double> &row_constraints,
                  const Vector<double>            &u,
                  const Vector<double>            &u_tilde,
                  const double                     mass_coefficient,
                  const double                     time,
                  Vector<double>                  &residual,
                  const bool                       with_tangent);

    /// Throws InvertedElementError, naming the inverted cells of @p u, if
    /// J <= 0 for a material that cannot represent inversion.
    void
    check_not_inverted(const double                     J,
                       const materials::Interface<dim> &material,
                       const Vector<double>            &u) const;
  };
} // namespace tissuefem::solid
