#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/base/point.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/base/parallel.h>
#include <tissuefem/materials/material_set.h>
#include <tissuefem/solid/discretization.h>
#include <tissuefem/solid/fibre_field.h>
#include <tissuefem/solid/nodal_dilatation.h>
#include <tissuefem/solvers/linear_solver.h>

#include <array>
#include <cstdint>
#include <tuple>
#include <vector>

namespace tissuefem::solid
{
  /**
   * The nodal dilatation's Newton systems with P1's stencil. The exact
   * tangent of the nodally averaged dilatation (NodalDilatation) couples
   * vertices up to three edges apart: a wide matrix, expensive to assemble
   * and to factor (doc/studies.md, "What the nodal dilatation costs").
   * With J_b = sum_{g at b} V_g J_g / V_b the dilatation of vertex b, Z_b =
   * dJ_b/du its gradient, and per cell e with Jbar_e = sum_{b in e} J_b /
   * (d + 1) and Psi-hat_e = V_e Psi(Fbar_e) (derivatives phi_F, phi_theta,
   * ...), the tangent is
   *
   *   K = A + Y^T Z + Z^T Y + Z^T H Z,
   *
   * where A holds each cell's phi_FF and the pressures' second derivatives
   * of J (pi_b = sum_{e at b} phi_theta_e / (d + 1) at the vertices), Y_b =
   * sum_{e at b} phi_Ftheta_e : dF_e / (d + 1) and H_bc = sum_{e at b, c}
   * phi_thetatheta_e / (d + 1)^2. Every block couples only the vertices of
   * one cell. With s = Z du (the vertices' dilatation increments) and p =
   * H s + Y du as unknowns, K du = b is the same as
   *
   *   [ A  Y^T  Z^T ] [du]   [b]
   *   [ Y  H    -I  ] [s ] = [0]
   *   [ Z  -I   0   ] [p ]   [0],
   *
   * a symmetric indefinite system with plain P1's stencil and dim + 2
   * unknowns per vertex, which a sparse LU with pivoting (MUMPS, KLU,
   * UMFPACK) factors for about the cost of P1's own (Newton's iterates are
   * those of the wide matrix: only the way of solving changes).
   *
   * Unknowns: the displacement's n_u, then s and p numbered by vertex as
   * the first component's dof divided by dim (deal.II gives each vertex of
   * a P1 system dim consecutive dofs), so that a process owns the s and p
   * of the vertices whose displacement it owns.
   */
  template <int dim>
  class NodalDilatationSystem
  {
  public:
    /// Whether the system can be built: dim >= 2, each vertex's dofs
    /// consecutive from a multiple of dim, and @p constraints without
    /// hanging nodes (every line without entries).
    static bool
    applies(const NodalDilatation<dim>      &nodal,
            const AffineConstraints<double> &constraints);

    /**
     * Inertia and gravity, added to the displacement rows of each cell's
     * block when the Jacobian is assembled through the lean path: one
     * insertion per cell instead of a second pass of the lean kernel into
     * the P1 matrix (a third of the nodal dilatation's assembly on the
     * 9,600-tetrahedra box). The closed-form P1 mass and gravity load of
     * LinearSimplexKernel.
     */
    struct Loads
    {
      /// Ghosted w: the residual gets M w (null: none).
      const VectorType *inertia = nullptr;
      /// The Jacobian gets this times M.
      double mass_coefficient = 0;
      /// M is the row-sum lumped mass ('Finite element/Mass').
      bool lumped_mass = false;
      /// Acceleration of gravity, load factor included (length/time^2);
      /// the residual gets minus its load.
      Tensor<1, dim> gravity;
    };

    /// For the mesh of @p discretization and its patches @p nodal.
    NodalDilatationSystem(const Discretization<dim>  &discretization,
                          const NodalDilatation<dim> &nodal);

    /**
     * Assembles the elastic part under the constraints @p rows
     * (inhomogeneous: the Dirichlet increment lifted, as deal.II does):
     * with @p jacobian the cells' blocks of the system and its right-hand
     * side (finish() adds the residual's rows to the residual), else the
     * elastic residual into @p residual (the same as
     * NodalDilatation::assemble()'s, in O(cells) instead of O(cells times
     * patch)). With @p loads (only with @p jacobian) inertia and gravity
     * too. Returns the cells where Fbar is undefined, as
     * NodalDilatation::assemble().
     */
    std::vector<std::tuple<unsigned int, double, Point<dim>>>
    assemble(const VectorType                  &u,
             const materials::MaterialSet<dim> &materials,
             const FibreField<dim>             &fibres,
             const AffineConstraints<double>   &rows,
             const bool                         inhomogeneous,
             const bool                         jacobian,
             VectorType                        &residual,
             const Loads                       *loads = nullptr);

    /// Forgets the last assembly's blocks (before the next one).
    void
    clear();

    /// After assemble() (or alone, with no elastic part): adds the rest of
    /// the displacement block (inertia, the loads' and contributions'
    /// derivatives, constrained rows) from the compressed P1 matrix @p uu
    /// (null: it has nothing to add), and the elastic residual to the
    /// compressed @p residual.
    void
    finish(const MatrixType *uu, VectorType &residual);

    /// The system's matrix (after finish()).
    const MatrixType &
    system_matrix() const
    {
      return matrix;
    }

    /// Solves K x = b through the system: @p b the negated residual of the
    /// last assembly (its lifted rows too).
    void
    solve(solvers::LinearSolver &solver,
          VectorType            &x,
          const VectorType      &b,
          const bool             refactorize);

  private:
    /// The local system of owned cell @p g: rows and columns its
    /// displacement dofs, then s and p at its vertices. @p psi: the cell's
    /// Psi-hat derivatives (null where undefined: then only the terms of
    /// its J, which the neighbours' pressures weigh).
    void
    add_cell(const unsigned int              g,
             const MeanDilatationPoint<dim> *psi,
             const double                    J,
             const Tensor<2, dim>           &cofactor,
             const bool                      jacobian,
             FullMatrix<double>             &K,
             Vector<double>                 &r) const;

    /// Adds @p loads on cell @p g of density @p rho to its block @p K and
    /// vector @p r (displacement rows and columns).
    void
    add_loads(const unsigned int  g,
              const Loads        &loads,
              const double        rho,
              FullMatrix<double> &K,
              Vector<double>     &r) const;

    /// The augmented indices of owned cell @p g's rows: its displacement
    /// dofs, then s and p at its vertices.
    void
    local_indices(const unsigned int                    g,
                  std::vector<types::global_dof_index> &indices) const;

    /// Fills direct and pressure_entry (after the matrix is built).
    void
    build_direct_access(const AffineConstraints<double> &constraints);

    /// F, J and J F^{-T} of every cell here for the ghosted @p u, in
    /// parallel, reading @p u through ghost_index.
    void
    deformation(const VectorType            &u,
                std::vector<Tensor<2, dim>> &F,
                std::vector<double>         &J,
                std::vector<Tensor<2, dim>> &cofactor);

    /// Splits the direct cells' rows among the threads by vertex (parts,
    /// others).
    void
    build_parts();

    /// The Jacobian's cell blocks (with @p loads, if given) into the
    /// system: the direct cells in parallel over parts, the others through
    /// the constraints. @p psi per cell as add_cell() takes it.
    void
    add_blocks(const std::vector<const MeanDilatationPoint<dim> *> &psi,
               const std::vector<double>                           &J,
               const std::vector<Tensor<2, dim>>                   &cofactor,
               const materials::MaterialSet<dim>                   &materials,
               const Loads                                         *loads,
               const bool inhomogeneous);

    /// The residual alone (the line search's trials): each owned cell's
    /// displacement rows computed in parallel, then added in a fixed order.
    /// @p psi per cell as add_cell() takes it.
    void
    add_residual(const std::vector<const MeanDilatationPoint<dim> *> &psi,
                 const std::vector<double>                           &J,
                 const std::vector<Tensor<2, dim>>                   &cofactor,
                 const AffineConstraints<double>                     &rows,
                 VectorType                                          &residual);

    const NodalDilatation<dim> &nodal;
    /// Indices into @p nodal's cells of the owned ones.
    std::vector<unsigned int> owned_cells;
    types::global_dof_index   n_u = 0, n_vertices = 0;
    /// Of the augmented unknowns.
    IndexSet owned, relevant;
    /// Per cell of @p nodal: the index of s at each vertex (that of p is
    /// n_vertices further), and V_g / V_b.
    std::vector<std::array<types::global_dof_index, dim + 1>> s_index;
    std::vector<std::array<double, dim + 1>>                  share;
    MatrixType                                                matrix;
    /// The assembled right-hand side (writable ghosts); the rows of s and
    /// p carry the lifting's terms.
    VectorType rhs;
    /// Pressures pi_b: summed over this process's cells, then ghosted.
    VectorType                pressure_sum, pressure;
    AffineConstraints<double> augmented_rows;
    /// In-place access for owned cells without constrained dofs: per owned
    /// cell (in owned_cells' order) its rows' local indices (-1 for the
    /// other cells) and each entry's position in its row; the rows' values.
    struct
    {
      std::vector<int>           row;
      std::vector<std::uint16_t> entry; ///< rows are short (< 2^16 entries)
      std::vector<double *>      row_values;
    } direct;
    /// Per cell and vertex, the local index of pi_b in @p pressure.
    std::vector<std::array<int, dim + 1>> pressure_entry;
    /// Where the P1 matrix's rows and entries lie here (finish(), add_block()).
    std::vector<int> uu_row, uu_entry;
    /// Per cell of @p nodal and dof, its index in the ghosted vectors
    /// (Trilinos' local index, the same for every ghosted vector of the
    /// mesh): read without a global-to-local search per entry. Built on
    /// the first assembly, for vectors of ghost_length entries.
    std::vector<int> ghost_index;
    int              ghost_length = -1;
    /// The residual alone: per owned cell its displacement rows.
    std::vector<double> cell_residuals;
    /// The Jacobian's insertion without locks: per thread the direct owned
    /// cells (positions in owned_cells) with a vertex in its range of
    /// vertices and which of their rows lie there (bit i: row i); every
    /// row belongs to one range. others: the owned cells with constrained
    /// or other processes' rows. Built on the first Jacobian.
    std::vector<std::vector<std::pair<unsigned int, std::uint32_t>>> parts;
    std::vector<unsigned int>                                        others;
  };
} // namespace tissuefem::solid
