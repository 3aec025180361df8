#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

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
  };

  /**
   * Solves the Newton systems: UMFPACK's sparse LU, or conjugate gradients
   * preconditioned by Trilinos ML algebraic multigrid (for symmetric positive
   * definite Jacobians, i.e. away from instabilities).
   */
  class LinearSolver
  {
  public:
    explicit LinearSolver(const LinearSolverParameters &parameters);

    /// Near-null-space vectors for AMG (one mask per displacement component).
    void
    set_constant_modes(const std::vector<std::vector<bool>> &modes);

    /// Solves A x = b; throws SolverError if the solver fails.
    void
    solve(const SparseMatrix<double> &A,
          Vector<double>             &x,
          const Vector<double>       &b) const;

  private:
    LinearSolverParameters         parameters;
    std::vector<std::vector<bool>> constant_modes;
  };
} // namespace tissuefem::solvers
