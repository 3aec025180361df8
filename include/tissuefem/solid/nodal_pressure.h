#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/base/point.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/base/parallel.h>
#include <tissuefem/materials/material_set.h>
#include <tissuefem/solid/discretization.h>
#include <tissuefem/solid/fibre_field.h>
#include <tissuefem/solid/nodal_dilatation.h>
#include <tissuefem/solvers/linear_solver.h>

#include <array>
#include <cstdint>
#include <memory>
#include <tuple>
#include <vector>

namespace tissuefem::solid
{
  /**
   * The linear simplex with one pressure per vertex (P1-P1) and Dohrmann and
   * Bochev's (2004) projection stabilization, for models whose energy has a
   * volumetric part, Psi = Psi_rest(F) + lambda/2 g(J)^2
   * (materials::VolumetricPart). The pressure p_h = sum_i p_i N_i replaces
   * lambda g(J) weakly:
   *
   *   W(u) = sum_e V_e (Psi - lambda/2 g^2)(F_e) + max_p (p^T b - p^T A p / 2),
   *   b_i  = int N_i g(J) dV,
   *   A    = int N_i N_j / lambda + alpha (N_i - Pi_0 N_i)(N_j - Pi_0 N_j) /
   * mu,
   *
   * with Pi_0 the projection onto constants per cell (alpha = 'Stabilization
   * factor'). The pressure is eliminated: p = A^{-1} b(u), A fixed per mesh
   * (reference configuration) and factorized once, so the state is the
   * displacement alone (explicit and implicit integrators, checkpoints and
   * mesh changes as for plain P1) and W(u) = sum_e V_e (Psi - lambda/2 g^2 +
   * g pbar_e / 2), pbar_e the mean of the cell's vertex pressures. Its
   * Newton systems keep p as an unknown,
   *
   *   [ K  B^T ] [du]   [-R]
   *   [ B  -A  ] [dp] = [ 0],   B_i = db_i/du,
   *
   * (K: the cells' (Psi - lambda/2 g^2)'' plus pbar_e g''), a symmetric
   * indefinite system with plain P1's stencil and dim + 1 unknowns per
   * vertex, one fewer than the nodal dilatation's (doc/studies.md, "The
   * four-unknown element").
   *
   * Unknowns of the system: the displacement's n_u, then p numbered by
   * vertex as the first component's dof divided by dim, so that a process
   * owns the pressures of the vertices whose displacement it owns.
   */
  template <int dim>
  class NodalPressure
  {
  public:
    /// For the mesh of @p discretization, its P1 cells @p cells (owned and
    /// around), the models of @p materials (each with a volumetric part).
    NodalPressure(const Discretization<dim>         &discretization,
                  const NodalDilatation<dim>        &cells,
                  const materials::MaterialSet<dim> &materials,
                  const double                       stabilization);

    /// The mean vertex pressure pbar_e of each owned cell by active cell
    /// index (0 elsewhere), for the ghosted displacement @p u.
    std::vector<double>
    cell_pressures(const VectorType                  &u,
                   const materials::MaterialSet<dim> &materials);

    /**
     * The elastic residual dW/du for the ghosted @p u under the constraints
     * @p rows; with @p jacobian (only with a system, build_system()) the
     * cells' blocks of the system and its right-hand side instead (finish()
     * adds the residual's rows). Returns the cells where the model is
     * undefined (det F <= 0 without inversion), which contribute nothing.
     */
    std::vector<std::tuple<unsigned int, double, Point<dim>>>
    assemble(const VectorType                  &u,
             const materials::MaterialSet<dim> &materials,
             const FibreField<dim>             &fibres,
             const AffineConstraints<double>   &rows,
             const bool                         inhomogeneous,
             const bool                         jacobian,
             VectorType                        &residual);

    /// Lays out the Newton system for @p constraints (no hanging nodes);
    /// null: none (residuals only).
    void
    build_system(const AffineConstraints<double> *constraints);

    bool
    has_system() const
    {
      return system_built;
    }

    const MatrixType &
    system_matrix() const
    {
      return matrix;
    }

    /// Forgets the last Jacobian's blocks.
    void
    clear();

    /// After assemble() with a Jacobian: adds the compressed displacement
    /// block @p uu (inertia, contributions, constrained rows; null: none)
    /// and the elastic residual to the compressed @p residual.
    void
    finish(const MatrixType *uu, VectorType &residual);

    /// Solves K du = b through the system, @p b the negated residual of
    /// the last assembly.
    void
    solve(solvers::LinearSolver &solver,
          VectorType            &x,
          const VectorType      &b,
          const bool             refactorize);

    std::size_t
    memory_consumption() const;

  private:
    /// p = A^{-1} b(u) into pressure (ghosted) and each owned cell's pbar,
    /// from the cells' J (deformation()).
    void
    solve_pressures(const materials::MaterialSet<dim> &materials);

    /// Fills direct_row, direct_entry and row_values (after the matrix is
    /// built).
    void
    build_direct_access(const AffineConstraints<double> &constraints);

    /// F, J and J F^{-T} of every owned cell for the ghosted @p u.
    void
    deformation(const VectorType &u);

    /// One owned cell's rows (displacement, then pressure at its vertices)
    /// and, with @p K, its block.
    void
    add_cell(const unsigned int               o,
             const materials::Interface<dim> &material,
             const Tensor<1, dim>            &fibre,
             const materials::TangentMethod   method,
             Vector<double>                  &r,
             FullMatrix<double>              *K) const;

    /// Adds owned cell @p o's rows @p r and, with @p K, its block: into the
    /// system (in place where its rows are owned and free, else through
    /// the lifted constraints), else into @p residual through @p rows.
    void
    add_rows(const unsigned int               o,
             const Vector<double>            &r,
             const FullMatrix<double>        *K,
             const AffineConstraints<double> &rows,
             const bool                       inhomogeneous,
             VectorType                      &residual);

    const NodalDilatation<dim> &nodal;
    const double                stabilization;
    /// Indices into nodal's cells of the owned ones; per owned cell the
    /// pressure index (vertex) of each node, lambda and mu.
    std::vector<unsigned int>                                 owned_cells;
    std::vector<std::array<types::global_dof_index, dim + 1>> vertex;
    std::vector<std::array<double, 2>>                        moduli;
    types::global_dof_index n_u = 0, n_active_cells = 0;
    IndexSet                owned_p, relevant_p;
    /// A and its factorization (Amesos' KLU: a scalar P1 matrix).
    MatrixType                                      A;
    SolverControl                                   control;
    std::unique_ptr<TrilinosWrappers::SolverDirect> factorization;
    /// b (writable ghosts), its owned part, p, p ghosted.
    VectorType b, owned_b, p, pressure;
    /// Per owned cell: F, J, J F^{-T}, pbar.
    std::vector<Tensor<2, dim>> F, cofactor;
    std::vector<double>         J, pbar;
    /// The Newton system (build_system()); its unknowns owned and needed
    /// here (set with the mesh).
    bool                      system_built = false;
    IndexSet                  owned, relevant;
    MatrixType                matrix;
    VectorType                rhs;
    AffineConstraints<double> augmented_rows;
    std::vector<int>          uu_row, uu_entry;
    /// In-place insertion for owned cells whose displacement dofs are all
    /// owned and free (then so are their pressures): per owned cell its
    /// rows' local indices (-1 for the other cells) and each entry's
    /// position in its row; the rows' values.
    std::vector<int>           direct_row;
    std::vector<std::uint16_t> direct_entry;
    std::vector<double *>      row_values;
    /// Per owned cell and dof its index in the ghosted displacement
    /// vectors (Trilinos' local index; built for vectors of ghost_length
    /// entries), and its row in the residual where the cell's dofs are all
    /// owned and free under the solid's constraints (else -1).
    std::vector<int> ghost_index, residual_row;
    int              ghost_length = -1;
    /// assemble()'s work space: a chunk of cells' rows and blocks, and
    /// which are undefined.
    std::vector<Vector<double>>     cell_rows;
    std::vector<FullMatrix<double>> cell_blocks;
    std::vector<char>               cell_undefined;
    /// Per owned cell and vertex the local index of its pressure in
    /// @p pressure.
    std::vector<int> pressure_index;
  };
} // namespace tissuefem::solid
