// Every registered linear solver ('Linear solver/Type') against
// manufactured solutions: x chosen at random (fixed seed), b = A x, on a
// 2D five-point Laplacian (symmetric positive definite, as Newton's
// matrices of stable states are) whose rows are split among the processes.
// Each method must recover x (direct: to 1e-12 relative, iterative: to
// 1e-6, from 'Relative tolerance' 1e-10), again for a second right-hand
// side without refactorizing, again after the matrix values change, and
// on a new matrix object of another pattern (the kept state is dropped);
// a loose forcing term must still meet its residual bound; an iterative
// one starts from the caller's guess only when told to, and then needs
// no iteration at the answer and fewer near it. Direct methods
// must also solve symmetric indefinite and unsymmetric systems met in turn
// on one matrix object (MUMPS, with its symmetric factorization allowed,
// factorizes the symmetric ones as L D L^T). Checks
// are gathered over the registered methods, so this output does not change when
// one is added; a method that refuses the number of processes must say so
// naming the parameter.

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/solvers/linear_solver.h>

#include "../tests.h"
#include "laplacian.h"

#include <cmath>
#include <string>

using namespace dealii;
using namespace tissuefem;

namespace
{
  using tissuefem_tests::laplacian;
  using tissuefem_tests::owned_rows;
  using tissuefem_tests::random_vector;
  using tissuefem_tests::relative_error;

  /// Solves A x = A exact and checks x against exact.
  void
  check_solve(const std::string     &name,
              solvers::LinearSolver &solver,
              const MatrixType      &A,
              const std::uint64_t    seed,
              const bool             refactorize,
              const std::string     &what)
  {
    const VectorType exact = random_vector(A, seed);
    VectorType       b(exact), x(exact);
    A.vmult(b, exact);
    x = 0;
    solver.solve(A, x, b, refactorize);
    const double error = relative_error(x, exact);
    tissuefem_tests::check(error <= (solver.direct() ? 1e-12 : 1e-6),
                           "solver " + name + what,
                           "relative error " + std::to_string(error));
  }

  /**
   * Direct solvers on matrices Newton also meets: symmetric indefinite
   * (a stiffness past a limit point, the nodal dilatation's saddle point)
   * and not symmetric (friction), on the same matrix object in turn, so
   * that a method that factorizes symmetric matrices otherwise must notice
   * the change both ways (MUMPS analyses again each time; the LUs never).
   * Iterative methods (CG) are not asked.
   */
  void
  check_structure(const std::string &name, MatrixType &A)
  {
    // The method with its symmetric factorizations allowed (an entry of
    // MUMPS's that the others ignore).
    ParameterHandler prm;
    solvers::LinearSolver::declare_parameters(prm);
    prm.enter_subsection("Linear solver");
    prm.set("Type", name);
    prm.set("MUMPS symmetric factorization", true);
    prm.leave_subsection();
    solvers::LinearSolver solver(prm);
    const std::string     what = " solves symmetric indefinite and unsymmetric "
                                 "systems in turn (direct methods)";
    if (!solver.direct())
      {
        tissuefem_tests::check(true, "solver " + name + what);
        tissuefem_tests::check(true,
                               "solver " + name
                                 + " analyses again only where symmetry "
                                   "decides the factorization");
        return;
      }
    // Analyses after the first solve's (which every method makes).
    unsigned int setups = 0;
    double       worst  = 0;
    unsigned int seed   = 10;
    for (const double skew : {0., 0.7, 0.})
      {
        // Eigenvalues of the Laplacian lie in (0, 8); a shift of -2.9
        // leaves some on either side of zero, none nearer than 0.014. The
        // unsymmetric one is kept diagonally dominant (shift 1), as
        // skewed and indefinite it is badly conditioned.
        laplacian(A, 24, false, 1., skew == 0 ? -2.9 : 1., skew);
        const VectorType exact = random_vector(A, ++seed);
        VectorType       b(exact), x(exact);
        A.vmult(b, exact);
        x = 0;
        solver.solve(A, x, b, true);
        tissuefem_tests::raise(worst, relative_error(x, exact));
        if (seed == 11)
          setups = solver.statistics().setups;
      }
    tissuefem_tests::check(worst <= 1e-10,
                           "solver " + name + what,
                           "relative error " + std::to_string(worst));
    const unsigned int analyses = solver.statistics().setups - setups;
    tissuefem_tests::check(analyses == (name == "MUMPS" ? 2u : 0u),
                           "solver " + name
                             + " analyses again only where symmetry "
                               "decides the factorization",
                           std::to_string(analyses) + " analyses");
    laplacian(A, 24, false, 3., 1.);
  }


  void
  check_method(const std::string &name)
  {
    std::unique_ptr<solvers::LinearSolver> solver;
    try
      {
        solver = solvers::LinearSolver::with_defaults(name);
      }
    catch (const InputError &e)
      {
        const std::string message = e.what();
        tissuefem_tests::check(parallel_tools::n_processes() > 1
                                 && message.find("Linear solver/Type")
                                      != std::string::npos,
                               "solver " + name
                                 + " runs here or refuses naming the "
                                   "parameter",
                               message);
        return;
      }
    tissuefem_tests::check(true,
                           "solver " + name
                             + " runs here or refuses naming the parameter");
    MatrixType A;
    laplacian(A, 24, false, 1., 0.);
    check_solve(name, *solver, A, 1, true, " recovers a manufactured solution");
    const auto kept = solver->statistics();
    check_solve(name, *solver, A, 2, false, " solves a second right-hand side");
    tissuefem_tests::check(solver->statistics().setups == kept.setups
                             && solver->statistics().factorizations
                                  == kept.factorizations,
                           "solver " + name
                             + " keeps its factorization or hierarchy for it");
    // New values without refactorizing: a direct solver solves with the
    // factorization it keeps (of the old values: x = A_old^-1 b, what a
    // kept Jacobian or quasi-Newton Hessian relies on); an iterative one
    // with the matrix as it is.
    {
      const VectorType exact = random_vector(A, 6);
      VectorType       b(exact), x(exact);
      A.vmult(b, exact);
      laplacian(A, 24, false, 3., 1.);
      const std::string what = " without refactorizing: direct solvers "
                               "keep their factorization, iterative ones "
                               "follow the matrix";
      if (solver->direct())
        {
          x = 0;
          solver->solve(A, x, b, false);
          const double error = relative_error(x, exact);
          tissuefem_tests::check(error <= 1e-12,
                                 "solver " + name + what,
                                 "relative error " + std::to_string(error));
        }
      else
        check_solve(name, *solver, A, 7, false, what);
    }
    check_solve(name, *solver, A, 3, true, " follows new matrix values");
    check_structure(name, A);
    MatrixType chain;
    laplacian(chain, 300, true, 1., 1e-2);
    check_solve(
      name, *solver, chain, 4, true, " follows a new matrix and pattern");

    // A loose forcing term still bounds the residual, and an iterative
    // solver takes fewer iterations for it than for its own tolerance (on
    // a grid large enough for AMG to be no exact solver).
    MatrixType large;
    laplacian(large, 100, false, 1., 0.);
    const VectorType exact = random_vector(large, 5);
    VectorType       b(exact), x(exact), r(exact);
    large.vmult(b, exact);
    const unsigned int before = solver->statistics().iterations;
    solver->solve(large, x, b, true, 1e-3);
    const unsigned int loose = solver->statistics().iterations - before;
    large.residual(r, x, b);
    tissuefem_tests::check(r.l2_norm() <= 1e-3 * b.l2_norm(),
                           "solver " + name
                             + " meets a loose forcing term's bound",
                           std::to_string(r.l2_norm() / b.l2_norm()));
    solver->solve(large, x, b, true);
    const unsigned int tight = solver->statistics().iterations - before - loose;
    tissuefem_tests::check(solver->direct() || loose < tight,
                           "solver " + name
                             + " iterates less for a loose forcing term",
                           std::to_string(loose) + " against "
                             + std::to_string(tight));

    // A guess (the linearly implicit Euler's h v_n): an iterative solver
    // starts there only when told, and then stops as soon as the same test
    // holds; a direct one solves as ever.
    const auto iterations_from = [&](VectorType &start, const bool guess) {
      const unsigned int first = solver->statistics().iterations;
      solver->solve(large, start, b, true, 0, guess);
      return solver->statistics().iterations - first;
    };
    VectorType near(exact), perturbation = random_vector(large, 8);
    near.add(1e-4, perturbation);
    x                             = 0;
    const unsigned int from_zero  = iterations_from(x, true);
    x                             = exact;
    const unsigned int ignored    = iterations_from(x, false);
    x                             = exact;
    const unsigned int at_answer  = iterations_from(x, true);
    x                             = near;
    const unsigned int from_near  = iterations_from(x, true);
    const double       near_error = relative_error(x, exact);
    tissuefem_tests::check(ignored == from_zero,
                           "solver " + name
                             + " starts from zero unless given a guess",
                           std::to_string(ignored) + " from the answer "
                             + "not given as a guess, against "
                             + std::to_string(from_zero) + " from zero");
    tissuefem_tests::check(near_error <= (solver->direct() ? 1e-12 : 1e-6),
                           "solver " + name
                             + " recovers the answer from a "
                               "guess near it",
                           "relative error " + std::to_string(near_error));
    tissuefem_tests::check(solver->direct()
                             || (at_answer == 0 && from_near < from_zero),
                           "solver " + name
                             + " iterates less from a guess near the answer",
                           std::to_string(at_answer) + " from the answer, "
                             + std::to_string(from_near) + " near it, "
                             + std::to_string(from_zero) + " from zero");
    // What a direct solver keeps refers to the matrix: forget it before
    // the matrices go.
    solver->reset();
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  tissuefem_tests::OneWriter       writer;
  {
    tissuefem_tests::EachModel each("solver", "each registered method");
    for (const auto &[name, entry] :
         solvers::linear::LinearSolverRegistry::instance().all())
      {
        each.model(name);
        check_method(name);
      }
  }
  return tissuefem_tests::exit_status();
}
