#pragma once

#include <tissuefem/base/parallel.h>
#include <tissuefem/solvers/linear/interface.h>

#include <future>
#include <memory>

namespace tissuefem::solvers
{
  using namespace dealii;

  /**
   * Sparse LU factorizations (KLU) made on a thread of their own while
   * the caller goes on solving with the last one finished: what a W-method
   * at a haptic rate needs (the linearly implicit Euler with 'Background
   * factorization'), whose steps may solve with the Jacobian of a few
   * steps before but must not wait the 10-15 ms of a factorization every
   * few steps (doc/studies.md, "Speed, measured").
   *
   * solve(A, x, b, refactorize):
   * - a finished factorization is adopted first (it becomes the one used);
   * - with none at all (the first solve, after reset()), A is factorized
   *   at once and the call waits for it;
   * - with @p refactorize, a factorization of A's present values starts in
   *   the background (A is copied before the call returns; one still
   *   running is waited for and adopted first, so that the factors in use
   *   are at most one request old), and this solve uses the factors it
   *   had.
   *
   * One MPI process only: the copy lives on an Epetra_SerialComm, so that
   * the factorizing thread communicates over no MPI communicator while
   * the caller's thread may (deal.II initializes MPI with
   * MPI_THREAD_SERIALIZED; Amesos' timers still call MPI_Wtime, a local
   * clock read in Open MPI and MPICH). The result
   * depends on when the thread finishes; for a matrix that does not
   * change (a linear body at a fixed step) every factorization is of the
   * same matrix and the answers are exact.
   */
  class BackgroundFactorization
  {
  public:
    BackgroundFactorization();
    /// Waits for a running factorization.
    ~BackgroundFactorization();

    /// x = A_k^{-1} b, A_k the matrix of the factorization in use (see
    /// the class documentation). Throws SolverError where a factorization
    /// fails (a singular matrix), when it is adopted.
    void
    solve(const MatrixType       &A,
          VectorType             &x,
          const VectorType       &b,
          const bool              refactorize,
          LinearSolverStatistics &stats);

    /// Waits for a running factorization and forgets every factorization
    /// and copy (the matrix's layout changed, or the factors in use are
    /// too far from the present matrix: a new step size).
    void
    reset();

    /// Waits for a running factorization and adopts it (for tests: makes
    /// the next solve use the last matrix given with refactorize).
    void
    wait(LinearSolverStatistics &stats);

    /// How many solves used factors of a matrix older than the one given
    /// with them (the steps the factorization's lag spared a wait).
    unsigned int
    lagged_solves() const
    {
      return lagged;
    }

  private:
    /// One factorization: a serial copy of the matrix and its KLU factors.
    struct Factors;

    /// Copies @p A's values into @p target (its layout on first use).
    static void
    copy(const MatrixType &A, Factors &target);

    /// Adopts the running factorization if it is finished (@p block: waits
    /// for it).
    void
    adopt(const bool block, LinearSolverStatistics &stats);

    std::unique_ptr<Factors> current, spare;
    /// The factorization of spare under way (valid while one runs); its
    /// value is the seconds it took.
    std::future<double> running;
    /// Whether current's factors are of the matrix of the latest request.
    bool         up_to_date = false;
    unsigned int lagged     = 0;
  };
} // namespace tissuefem::solvers
