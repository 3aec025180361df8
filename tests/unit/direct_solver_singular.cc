// A singular system given to each direct solver (MUMPS, KLU, UMFPACK)
// fails with tissuefem's one-line SolverError saying so, and nothing of
// the solver's own reports reaches the terminal (this program's whole
// output is compared). A regular system of the same pattern solves to the
// exact answer (diagonal 1, 2, 3, right-hand side 1, 2, 3: x = 1, 1, 1).

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/solvers/linear_solver.h>

#include "../tests.h"

#include <cmath>
#include <string>

using namespace dealii;
using namespace tissuefem;

namespace
{
  /// "ok" with the solution's largest error, or the error's message.
  std::string
  solve(const std::string &type, const double last_diagonal)
  {
    const unsigned int n = 3;
    IndexSet           all(n);
    all.add_range(0, n);
    TrilinosWrappers::SparsityPattern pattern(all, MPI_COMM_WORLD);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        pattern.add(i, j);
    pattern.compress();
    MatrixType A;
    A.reinit(pattern);
    VectorType b(all, MPI_COMM_WORLD), x(all, MPI_COMM_WORLD);
    for (unsigned int i = 0; i < n; ++i)
      {
        A.set(i, i, i + 1 < n ? i + 1. : last_diagonal);
        b[i] = i + 1.;
      }
    A.compress(VectorOperation::insert);
    b.compress(VectorOperation::insert);

    const auto solver = solvers::LinearSolver::with_defaults(type);
    try
      {
        solver->solve(A, x, b);
      }
    catch (const SolverError &e)
      {
        return std::string("SolverError: ") + e.what();
      }
    double error = 0;
    for (unsigned int i = 0; i < n; ++i)
      tissuefem_tests::raise(error, std::abs(x[i] - 1.));
    return error < 1e-14 ? "ok" : "wrong answer";
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  for (const std::string type : {"MUMPS", "KLU", "UMFPACK"})
    {
      const std::string regular = solve(type, 3.);
      tissuefem_tests::check(regular == "ok",
                             type + ": a regular system solves",
                             regular);
      const std::string singular = solve(type, 0.);
      tissuefem_tests::check(singular.find("SolverError: ") == 0
                               && singular.find("singular") != std::string::npos
                               && singular.find('\n') == std::string::npos,
                             type
                               + ": a singular one fails in one line "
                                 "saying so",
                             singular);
      std::cout << type << ": " << singular << std::endl;
    }
  return tissuefem_tests::exit_status();
}
