#pragma once

#include <deal.II/base/parameter_handler.h>

#include <tissuefem/base/parallel.h>
#include <tissuefem/base/registry.h>

#include <memory>
#include <vector>

namespace tissuefem::solvers
{
  using namespace dealii;

  /// What a linear solver did since it was created.
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
} // namespace tissuefem::solvers


/**
 * The linear solvers Newton's systems J du = -R can be given to, one file
 * in source/solvers/linear/ each, registered under the names
 * 'Linear solver/Type' accepts. solvers::LinearSolver is what the rest of
 * the code holds: it picks one of these by name and reports failures
 * alike for all.
 */
namespace tissuefem::solvers::linear
{
  class Interface
  {
  public:
    virtual ~Interface() = default;

    /// Whether the method factorizes the matrix (a kept factorization may
    /// be reused for a new right-hand side: solve()'s @p refactorize).
    virtual bool
    direct() const = 0;

    /// Whether set_near_null_space() is of use (algebraic multigrid).
    virtual bool
    uses_near_null_space() const
    {
      return false;
    }

    /// Near-null-space vectors (rigid-body modes), distributed like the
    /// unknowns, whose dofs come in blocks of @p components consecutive
    /// indices per node.
    virtual void
    set_near_null_space(const std::vector<VectorType> &modes,
                        const unsigned int             components)
    {
      (void)modes;
      (void)components;
    }

    /// Forgets what was kept for the matrix (its layout changed, or it is
    /// about to be destroyed).
    virtual void
    reset()
      = 0;

    /**
     * Solves A x = b for a matrix whose layout is that of the previous call
     * unless reset() was called. An iterative method starts from @p x as
     * given (LinearSolver zeroes it unless its caller has a guess). Throws
     * SolverError (or lets a deal.II exception out) on failure. @p refactorize
     * false: a direct method reuses the factorization of the previous call as
     * is.
     * @p relative_tolerance > 0: an iterative method may stop at
     * |b - A x| <= that times |b| where that is looser than its own
     * tolerance. Counts what it did in @p stats.
     */
    virtual void
    solve(const MatrixType       &A,
          VectorType             &x,
          const VectorType       &b,
          const bool              refactorize,
          const double            relative_tolerance,
          LinearSolverStatistics &stats)
      = 0;
  };

  using LinearSolverRegistry = Registry<Interface, ParameterHandler &>;
} // namespace tissuefem::solvers::linear

/**
 * Registers a linear solver at the end of its source file, under @p name.
 * @p Class has a static declare_parameters(ParameterHandler &), which
 * declares its entries in the 'Linear solver' subsection (entries of the
 * same name declared by two solvers must agree), and a constructor taking
 * the ParameterHandler, which reads them.
 */
#define TISSUEFEM_REGISTER_LINEAR_SOLVER(Class, name, description)         \
  namespace                                                                \
  {                                                                        \
    const bool tissuefem_registered_##Class = [] {                         \
      ::tissuefem::solvers::linear::LinearSolverRegistry::instance().add(  \
        name,                                                              \
        description,                                                       \
        &Class::declare_parameters,                                        \
        [](::dealii::ParameterHandler &prm) {                              \
          return std::unique_ptr<::tissuefem::solvers::linear::Interface>( \
            std::make_unique<Class>(prm));                                 \
        });                                                                \
      return true;                                                         \
    }();                                                                   \
  }
