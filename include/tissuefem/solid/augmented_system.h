#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/lac/affine_constraints.h>

#include <tissuefem/base/parallel.h>
#include <tissuefem/solvers/linear_solver.h>

#include <vector>

/**
 * What the formulations' own Newton systems share (NodalDilatationSystem,
 * NodalPressure): the displacement's unknowns first, then unknowns of the
 * formulation's own at the vertices, numbered after them.
 */
namespace tissuefem::solid
{
  /// The vertices of the displacement dofs @p dofs, numbered as the first
  /// component's dof divided by @p dim (a P1 system gives each vertex dim
  /// consecutive dofs: NodalDilatationSystem::applies()).
  IndexSet
  vertex_set(const IndexSet &dofs, const unsigned int dim);

  /// @p dofs and @p copies unknowns at each of their vertices, the k-th
  /// numbered n_u + k n_vertices + vertex after the n_u = dofs.size()
  /// displacement unknowns: the augmented system's unknowns that a process
  /// owns (or needs) where it owns (needs) @p dofs.
  IndexSet
  with_vertex_unknowns(const IndexSet    &dofs,
                       const unsigned int dim,
                       const unsigned int copies);

  /// @p from's lines (Dirichlet values, no entries) on the augmented
  /// unknowns @p relevant, whose displacement part is numbered as
  /// @p from's.
  void
  copy_dirichlet_lines(const AffineConstraints<double> &from,
                       const IndexSet                  &relevant,
                       AffineConstraints<double>       &to);

  /**
   * Adds the entries of the compressed displacement block @p from into the
   * compressed @p to, whose rows and entries include them (the same
   * numbering): where they lie is found on the first call (@p row,
   * @p entry empty) and kept.
   */
  void
  add_block(const MatrixType &from,
            MatrixType       &to,
            std::vector<int> &row,
            std::vector<int> &entry);

  /**
   * After a Jacobian's cell blocks went into @p matrix and @p lifted:
   * compresses both, adds the displacement block @p uu (null: none) with
   * add_block(), and the displacement rows of @p lifted (the elastic
   * residual) to the compressed @p residual.
   */
  void
  finish_augmented(MatrixType       &matrix,
                   VectorType       &lifted,
                   const MatrixType *uu,
                   std::vector<int> &row,
                   std::vector<int> &entry,
                   VectorType       &residual);

  /**
   * Solves the augmented system @p matrix (owned unknowns @p owned) for
   * the displacement part @p x of its solution, with @p b the negated
   * residual of the displacement rows and @p lifted the assembled
   * right-hand side, whose other rows carry the lifting of the Dirichlet
   * increments; those are negated too (b = -R), used once and cleared (a
   * later solve with a kept factorization has none).
   */
  void
  solve_augmented(solvers::LinearSolver &solver,
                  const MatrixType      &matrix,
                  VectorType            &lifted,
                  const IndexSet        &owned,
                  VectorType            &x,
                  const VectorType      &b,
                  const bool             refactorize);
} // namespace tissuefem::solid
