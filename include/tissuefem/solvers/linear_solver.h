#pragma once

#include <deal.II/base/parameter_handler.h>

#include <tissuefem/base/parallel.h>

#include <memory>
#include <string>
#include <vector>

namespace tissuefem::solvers
{
  using namespace dealii;

  /// The 'Linear solver' subsection.
  struct LinearSolverParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    std::string  type;
    double       relative_tolerance;
    unsigned int max_iterations;
    double       rebuild_factor;
  };

  /// What the solver did since it was created.
  struct LinearSolverStatistics
  {
    unsigned int solves = 0;
    /// Krylov iterations summed over solves (0 for direct solvers).
    unsigned int iterations = 0;
    /// Symbolic factorizations or AMG hierarchies built.
    unsigned int setups = 0;
    /// Numeric factorizations (direct solvers).
    unsigned int factorizations = 0;
    double       setup_seconds  = 0;
  };

  /**
   * Solves the Newton systems J du = -R. Choices ('Linear solver/Type'):
   * - MUMPS (default, 'direct' is the same): parallel sparse LU through
   *   Trilinos Amesos; the symbolic analysis is done once per sparsity
   *   pattern and kept across Newton iterations and steps;
   * - KLU: Amesos' serial LU (the matrix is gathered on one process);
   *   symbolic analysis kept as for MUMPS;
   * - UMFPACK: SuiteSparse's LU, one process only; symbolic analysis kept;
   * - cg amg: conjugate gradients preconditioned by Trilinos ML algebraic
   *   multigrid whose near-null space is the rigid-body modes. The
   *   hierarchy is built once and kept across Newton iterations and steps
   *   while it works: it is rebuilt when a solve needs more than
   *   'AMG rebuild factor' times the iterations of the first solve after
   *   the last build, or fails.
   * Before the matrix is destroyed or reinitialized (the mesh changes),
   * call reset(): a kept factorization refers to it.
   */
  class LinearSolver
  {
  public:
    explicit LinearSolver(const LinearSolverParameters &parameters);
    ~LinearSolver();

    /// Near-null-space vectors for AMG (rigid-body modes), distributed like
    /// the unknowns, whose dofs come in blocks of @p components consecutive
    /// indices per node (as deal.II numbers an FESystem's dofs).
    void
    set_near_null_space(const std::vector<VectorType> &modes,
                        const unsigned int             components);

    /// Forgets factorizations and preconditioners (the matrix layout
    /// changed).
    void
    reset();

    /**
     * Solves A x = b for a matrix whose sparsity pattern is that of the
     * previous call unless reset() was called. Throws SolverError if the
     * solver fails. @p refactorize false reuses the numeric factorization
     * (direct solvers) of the previous call on the same matrix as is, for
     * methods that keep one matrix for many right-hand sides (simplified
     * Newton); iterative solvers keep their preconditioner anyway.
     * @p relative_tolerance > 0 asks an iterative solver for |b - A x| <=
     * that times |b| (an inexact Newton method's forcing term) instead of
     * 'Relative tolerance', when that is looser; direct solvers ignore
     * it.
     */
    void
    solve(const MatrixType &A,
          VectorType       &x,
          const VectorType &b,
          const bool        refactorize        = true,
          const double      relative_tolerance = 0);

    /// Whether the type is a sparse direct solver (not 'cg amg').
    bool
    direct() const
    {
      return parameters.type != "cg amg";
    }

    const LinearSolverStatistics &
    statistics() const
    {
      return stats;
    }

  private:
    class Implementation;
    LinearSolverParameters          parameters;
    std::unique_ptr<Implementation> implementation;
    LinearSolverStatistics          stats;
  };
} // namespace tissuefem::solvers
