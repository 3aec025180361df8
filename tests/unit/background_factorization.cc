// Factorizations on a thread of their own (solvers::BackgroundFactorization
// through LinearSolver::factorize_in_background, the linearly implicit
// Euler's 'Background factorization').
//
// Solver: on the 30 x 30 five-point Laplacian A_s (shift s on the
// diagonal), with b = A x for a random x:
// - the first solve has no factors yet, so it factorizes at once: x to
//   1e-12 relative;
// - after the values change to A_t, a solve that asks to refactorize
//   starts the factorization and answers with the old factors: it returns
//   A_s^{-1} b (to 1e-12), not A_t^{-1} b (off by more than 1e-3), and
//   counts one lagged solve;
// - once the thread is waited for, solves without refactorizing return
//   A_t^{-1} b (1e-12), equal to a synchronous KLU's answer;
// - a singular matrix given to the thread fails the next solve that
//   refactorizes, with a message that says so; a later solve of a regular
//   matrix works again;
// - a solver other than KLU is refused naming the parameter.
// Integrator: the one-element bar of the order tests (linear: every
// factorization is of the same matrix, so the lag cannot change the
// answer) under the linearly implicit Euler with 'Factorization interval =
// 5' and 'Background factorization': u(1) equals the oscillator's
// backward-Euler recursion (m = 1/3, k = 1) to 1e-9, and some solves did
// use lagged factors. On a neo-Hookean beam sagging under gravity (4 x 1 x
// 1, 8 x 2 x 2 boxes cut into tetrahedra, dt = 0.01 s, 40 steps) its final
// displacement differs from the synchronous W-method's (the same interval)
// by less than 0.5 % of the displacement (measured: 0.01-0.03 %), and from
// converged backward Euler's by at most three times the synchronous one's
// (measured: 1.3-1.7 times; the factors in use are as old at most, but
// of other steps).

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <tissuefem/app/parameters.h>
#include <tissuefem/base/input_error.h>
#include <tissuefem/solvers/linear_solver.h>

#include "../tests.h"
#include "laplacian.h"
#include "solid_scene.h"

#include <cmath>
#include <iostream>
#include <sstream>
#include <string>

using namespace dealii;
using namespace tissuefem;

namespace
{
  /// The m x m five-point Laplacian plus @p shift on the diagonal; a zero
  /// last row where @p singular.
  void
  laplacian(MatrixType        &A,
            const unsigned int m,
            const double       shift,
            const bool         singular = false)
  {
    tissuefem_tests::laplacian(A, m, false, 1., shift);
    if (!singular)
      return;
    const unsigned int last = m * m - 1;
    for (const unsigned int j : {last - m, last - 1, last})
      A.set(last, j, 0.);
    A.compress(VectorOperation::insert);
  }

  /// |A x - b| / |b|.
  double
  residual(const MatrixType &A, const VectorType &x, const VectorType &b)
  {
    VectorType r(b);
    A.vmult(r, x);
    r -= b;
    return r.l2_norm() / b.l2_norm();
  }

  void
  check_solver()
  {
    const unsigned int m = 30;
    MatrixType         A, A_old;
    laplacian(A, m, 0.5);
    laplacian(A_old, m, 0.5);
    VectorType              x(complete_index_set(m * m), MPI_COMM_WORLD), b(x);
    tissuefem_tests::Random random(20261129);
    for (unsigned int i = 0; i < m * m; ++i)
      x[i] = 1. + random.uniform();
    A.vmult(b, x);

    auto solver = solvers::LinearSolver::with_defaults("KLU");
    solver->factorize_in_background(true, "test");
    VectorType y(x);
    solver->solve(A, y, b, true);
    tissuefem_tests::check_small(residual(A, y, b),
                                 1e-12,
                                 "first solve: factorized at once, residual");

    // New values, a solve that asks to refactorize: the old factors answer.
    laplacian(A, m, 0.01);
    solver->solve(A, y, b, true);
    tissuefem_tests::check_small(
      residual(A_old, y, b),
      1e-12,
      "refactorizing solve: the old matrix's answer");
    tissuefem_tests::check(residual(A, y, b) > 1e-3,
                           "refactorizing solve: not yet the new matrix's",
                           "residual " + std::to_string(residual(A, y, b)));
    tissuefem_tests::check(solver->lagged_solves() == 1,
                           "one lagged solve counted",
                           std::to_string(solver->lagged_solves()));

    solver->wait_for_background();
    solver->solve(A, y, b, false);
    tissuefem_tests::check_small(residual(A, y, b),
                                 1e-12,
                                 "after the thread: the new matrix's answer");
    auto       synchronous = solvers::LinearSolver::with_defaults("KLU");
    VectorType z(x);
    synchronous->solve(A, z, b, true);
    z -= y;
    tissuefem_tests::check_small(z.l2_norm() / y.l2_norm(),
                                 1e-13,
                                 "equal to a synchronous KLU's answer");

    // A singular matrix: its factorization fails on the thread, and the
    // next refactorizing solve reports it.
    laplacian(A, m, 0.01, true);
    solver->solve(A, y, b, true);
    std::string message;
    try
      {
        solver->solve(A, y, b, true);
      }
    catch (const SolverError &e)
      {
        message = e.what();
      }
    tissuefem_tests::check(message.find("singular") != std::string::npos,
                           "a singular matrix's failure reported",
                           "message '" + message + "'");
    laplacian(A, m, 0.5);
    solver->solve(A, y, b, true);
    tissuefem_tests::check_small(residual(A, y, b),
                                 1e-12,
                                 "after the failure: factorized at once");

    std::string refusal;
    try
      {
        solvers::LinearSolver::with_defaults("MUMPS")->factorize_in_background(
          true,
          "Time integration/Linearly implicit Euler/Background "
          "factorization");
      }
    catch (const InputError &e)
      {
        refusal = e.what();
      }
    tissuefem_tests::check(refusal.find("Background factorization")
                               != std::string::npos
                             && refusal.find("KLU") != std::string::npos,
                           "MUMPS refused, naming the parameter",
                           "message '" + refusal + "'");
  }


  const std::string background_settings = R"(
      set Integrator = linearly implicit Euler
      subsection Linearly implicit Euler
        set Factorization interval   = 5
        set Background factorization = true
      end
)";

  void
  check_bar()
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string(
      tissuefem_tests::one_element_bar(background_settings)
      + "subsection Linear solver\n set Type = KLU\nend\n"
      + "subsection Time integration\n set Time step = 0.02\n"
        " set End time = 1\nend\n");
    tissuefem_tests::SolidScene<1> scene(prm);
    auto                           run = scene.start(prm);
    {
      const tissuefem_tests::Muted muted;
      run->advance_to(1.);
    }
    const Vector<double> u(run->state.u);
    tissuefem_tests::check_small(
      (u[u.size() - 1]
       - tissuefem_tests::one_element_bar_backward_euler(1. / 3))
        / tissuefem_tests::one_element_bar_backward_euler(1. / 3),
      1e-9,
      "bar: u(1) against the backward-Euler "
      "recursion, relative");
    tissuefem_tests::check(scene.linear_solver->lagged_solves() > 0,
                           "bar: solves used lagged factors",
                           "none did");

    // An interval of 1 factorizes every step's own matrix: refused.
    ParameterHandler every_step;
    declare_all_parameters(every_step);
    every_step.parse_input_from_string(tissuefem_tests::one_element_bar(R"(
      set Integrator = linearly implicit Euler
      subsection Linearly implicit Euler
        set Background factorization = true
      end
)") + "subsection Linear solver\n set Type = KLU\nend\n");
    tissuefem_tests::SolidScene<1> refused(every_step);
    std::string                    message;
    try
      {
        refused.start(every_step);
      }
    catch (const InputError &e)
      {
        message = e.what();
      }
    tissuefem_tests::check(message.find("Factorization interval")
                             != std::string::npos,
                           "bar: an interval of 1 refused, naming it",
                           "message '" + message + "'");
  }


  /// The final displacement of the sagging block with @p settings (the
  /// body of 'Time integration').
  Vector<double>
  sag(const std::string &settings)
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string(R"(
    set Dimension = 3
    subsection Geometry
      set Cell type    = simplex
      set Upper corner = 4, 1, 1
      set Subdivisions = 8, 2, 2
    end
    subsection Materials
      set Model           = neo-Hookean
      set Young's modulus = 100
      set Poisson's ratio = 0.3
      set Density         = 1
    end
    subsection Boundary conditions
      set Dirichlet = 0: xyz: 0; 0; 0
      set Gravity   = 0, 0, -9
    end
    subsection Linear solver
      set Type = KLU
    end
    subsection Time integration
      set Time step = 0.01
      set End time  = 0.4
)" + settings + "\nend\n");
    tissuefem_tests::SolidScene<3> scene(prm);
    auto                           run = scene.start(prm);
    {
      const tissuefem_tests::Muted muted;
      run->advance_to(0.4);
    }
    return Vector<double>(run->state.u);
  }

  void
  check_block()
  {
    const Vector<double> background  = sag(background_settings);
    const Vector<double> synchronous = sag(R"(
      set Integrator = linearly implicit Euler
      subsection Linearly implicit Euler
        set Factorization interval = 5
      end
)");
    const Vector<double> converged   = sag("set Integrator = backward Euler");
    Vector<double>       difference(background);
    difference -= synchronous;
    const double scale = converged.l2_norm();
    tissuefem_tests::check_small(difference.l2_norm() / scale,
                                 5e-3,
                                 "block: background against synchronous "
                                 "W-method, relative");
    Vector<double> error(background), synchronous_error(synchronous);
    error -= converged;
    synchronous_error -= converged;
    tissuefem_tests::check(error.l2_norm() <= 3 * synchronous_error.l2_norm(),
                           "block: error against converged backward Euler at "
                           "most three times the synchronous W-method's",
                           std::to_string(error.l2_norm() / scale) + " vs "
                             + std::to_string(synchronous_error.l2_norm()
                                              / scale));
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check_solver();
  check_bar();
  check_block();
  return tissuefem_tests::exit_status();
}
