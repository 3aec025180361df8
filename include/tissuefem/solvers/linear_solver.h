#pragma once

#include <deal.II/base/parameter_handler.h>

#include <tissuefem/base/parallel.h>
#include <tissuefem/solvers/background_factorization.h>
#include <tissuefem/solvers/linear/interface.h>

#include <memory>
#include <string>
#include <vector>

namespace tissuefem::solvers
{
  using namespace dealii;

  /**
   * Solves the Newton systems J du = -R with the method 'Linear solver/Type'
   * names, one of those registered in source/solvers/linear/ (MUMPS, KLU,
   * UMFPACK, cg amg, ...: linear::Interface). What every method shares is
   * here: the choice by name, forgetting what was kept when the matrix
   * object changes, the statistics, and one form of failure (SolverError
   * "linear solver (<type>) failed: why").
   * Before the matrix is destroyed or reinitialized (the mesh changes),
   * call reset(): a kept factorization refers to it.
   */
  class LinearSolver
  {
  public:
    /// The 'Linear solver' subsection: 'Type' and every registered
    /// method's own entries.
    static void
    declare_parameters(ParameterHandler &prm);

    /// The method 'Linear solver/Type' of @p prm names, reading its own
    /// entries.
    explicit LinearSolver(ParameterHandler &prm);

    /// The method @p type with its default settings.
    static std::unique_ptr<LinearSolver>
    with_defaults(const std::string &type);

    ~LinearSolver();

    /// Near-null-space vectors (rigid-body modes) for methods that use them
    /// (see uses_near_null_space()), distributed like the unknowns, whose
    /// dofs come in blocks of @p components consecutive indices per node
    /// (as deal.II numbers an FESystem's dofs).
    void
    set_near_null_space(const std::vector<VectorType> &modes,
                        const unsigned int             components);

    /// Whether set_near_null_space() is of use (algebraic multigrid).
    bool
    uses_near_null_space() const
    {
      return method->uses_near_null_space();
    }

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
     * it. @p from_guess: an iterative solver starts from @p x as given
     * (a predictor of the answer) instead of from zero; its stopping test
     * is the same, relative to |b|, so a good guess only saves iterations.
     * Direct solvers ignore it.
     */
    void
    solve(const MatrixType &A,
          VectorType       &x,
          const VectorType &b,
          const bool        refactorize        = true,
          const double      relative_tolerance = 0,
          const bool        from_guess         = false);

    /// Whether the method factorizes the matrix (not 'cg amg').
    bool
    direct() const
    {
      return method->direct();
    }

    /**
     * With @p on, solve() with @p refactorize true no longer waits for the
     * factorization: it is made on a thread of its own from a copy of the
     * matrix, and solves go on with the last one finished
     * (BackgroundFactorization), for W-methods whose steps may use a
     * Jacobian of a few steps before. Needs 'Type = KLU' and one MPI
     * process; @p parameter is named in the error otherwise.
     */
    void
    factorize_in_background(const bool on, const std::string &parameter);

    /// Waits for a background factorization and adopts it (for tests).
    void
    wait_for_background();

    /// Solves that used a background factorization of an older matrix
    /// than their own (0 without background factorization).
    unsigned int
    lagged_solves() const
    {
      return background ? background->lagged_solves() : 0;
    }

    /// The name the method was chosen by ('direct' reads 'MUMPS').
    const std::string &
    name() const
    {
      return type;
    }

    const LinearSolverStatistics &
    statistics() const
    {
      return stats;
    }

  private:
    std::string                        type;
    std::unique_ptr<linear::Interface> method;
    /// Set by factorize_in_background(true): then it solves, not method.
    std::unique_ptr<BackgroundFactorization> background;
    /// The matrix object the method's kept state belongs to.
    const void            *matrix = nullptr;
    LinearSolverStatistics stats;
  };
} // namespace tissuefem::solvers
