#include <tissuefem/base/input_error.h>
#include <tissuefem/base/timing.h>
#include <tissuefem/solvers/background_factorization.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_LinearProblem.h>
#include <Epetra_Map.h>
#include <Epetra_SerialComm.h>
#include <Epetra_Vector.h>
#include <Teuchos_ParameterList.hpp>

#ifdef __linux__
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

#include <algorithm>
#include <chrono>
#include <cstring>
#include <vector>

namespace tissuefem::solvers
{
  struct BackgroundFactorization::Factors
  {
    Epetra_SerialComm                  comm;
    std::unique_ptr<Epetra_Map>        rows, columns;
    std::unique_ptr<Epetra_CrsMatrix>  matrix;
    Epetra_LinearProblem               problem;
    std::unique_ptr<Amesos_BaseSolver> klu;

    /// The numeric factorization of the values copied last (the symbolic
    /// analysis on first use); returns its seconds. Runs on the
    /// background thread: no MPI communication (the copy's communicator
    /// is serial; Amesos' timers call MPI_Wtime, which makes none).
    double
    factorize()
    {
      const auto start = std::chrono::steady_clock::now();
      if (!klu)
        {
          problem.SetOperator(matrix.get());
          Amesos factory;
          klu.reset(factory.Create("Amesos_Klu", problem));
          if (!klu)
            throw SolverError("Amesos has no KLU");
          // Later factorizations reuse the pivot order, as the foreground
          // KLU does (source/solvers/linear/amesos_klu.cc).
          Teuchos::ParameterList parameters;
          parameters.set("Refactorize", true);
          klu->SetParameters(parameters);
          if (klu->SymbolicFactorization() != 0)
            throw SolverError("symbolic factorization failed (KLU)");
        }
      if (klu->NumericFactorization() != 0)
        throw SolverError("the matrix is singular or too badly conditioned "
                          "to factorize (KLU, in the background)");
      return seconds_since(start);
    }
  };


  BackgroundFactorization::BackgroundFactorization() = default;


  BackgroundFactorization::~BackgroundFactorization()
  {
    if (running.valid())
      running.wait();
  }


  void
  BackgroundFactorization::copy(const MatrixType &A, Factors &target)
  {
    const Epetra_CrsMatrix &M = A.trilinos_matrix();
    AssertThrow(M.Comm().NumProc() == 1,
                ExcMessage("background factorizations need one process"));
    const int n = M.NumMyRows();
    if (!target.matrix)
      {
        // The same global indices on a serial communicator: x and b are
        // then viewed, not copied, in solve().
        const auto &row_map = M.RowMap(), &column_map = M.ColMap();
        target.rows = std::make_unique<Epetra_Map>(
          -1, n, row_map.MyGlobalElements(), 0, target.comm);
        target.columns
          = std::make_unique<Epetra_Map>(-1,
                                         column_map.NumMyElements(),
                                         column_map.MyGlobalElements(),
                                         0,
                                         target.comm);
        std::vector<int> lengths(n);
        for (int i = 0; i < n; ++i)
          lengths[i] = M.NumMyEntries(i);
        target.matrix = std::make_unique<Epetra_CrsMatrix>(
          Copy, *target.rows, *target.columns, lengths.data(), true);
        for (int i = 0; i < n; ++i)
          {
            int     length;
            double *values;
            int    *indices;
            M.ExtractMyRowView(i, length, values, indices);
            target.matrix->InsertMyValues(i, length, values, indices);
          }
        target.matrix->FillComplete(*target.rows, *target.rows);
      }
    for (int i = 0; i < n; ++i)
      {
        int     length, copy_length;
        double *values, *copy_values;
        int    *indices, *copy_indices;
        M.ExtractMyRowView(i, length, values, indices);
        target.matrix->ExtractMyRowView(i,
                                        copy_length,
                                        copy_values,
                                        copy_indices);
        // Rows of an assembled matrix are sorted, so FillComplete kept
        // their order; a layout change resets the copies first
        // (LinearSolver::reset()), checked here before the copy.
        AssertThrow(length == copy_length, ExcInternalError());
        Assert(std::equal(indices, indices + length, copy_indices),
               ExcInternalError());
        std::memcpy(copy_values, values, length * sizeof(double));
      }
  }


  void
  BackgroundFactorization::adopt(const bool              block,
                                 LinearSolverStatistics &stats)
  {
    if (!running.valid())
      return;
    if (!block
        && running.wait_for(std::chrono::seconds(0))
             != std::future_status::ready)
      return;
    // get() rethrows the thread's SolverError; the spare is then left
    // without factors and dropped.
    double seconds;
    try
      {
        seconds = running.get();
      }
    catch (...)
      {
        spare.reset();
        throw;
      }
    std::swap(current, spare);
    up_to_date = true;
    ++stats.factorizations;
    stats.setup_seconds += seconds;
  }


  void
  BackgroundFactorization::solve(const MatrixType       &A,
                                 VectorType             &x,
                                 const VectorType       &b,
                                 const bool              refactorize,
                                 LinearSolverStatistics &stats)
  {
    adopt(false, stats);
    const bool none = !current || !current->klu;
    if (refactorize || none)
      {
        // At most one request in flight: the factors in use lag by one
        // request at most.
        adopt(true, stats);
        if (!spare)
          spare = std::make_unique<Factors>();
        copy(A, *spare);
        Factors *target = spare.get();
        running         = std::async(std::launch::async, [target] {
#ifdef __linux__
          // Below the stepping threads (Linux's nice value is per thread):
          // the factorization takes the cycles the steps leave.
          setpriority(PRIO_PROCESS, syscall(SYS_gettid), 10);
#endif
          return target->factorize();
        });
        up_to_date = false;
        if (none)
          adopt(true, stats);
      }
    if (!up_to_date)
      ++lagged;
    Epetra_Vector solution(View, *current->rows, x.trilinos_vector()[0]);
    Epetra_Vector rhs(View,
                      *current->rows,
                      const_cast<double *>(b.trilinos_vector()[0]));
    current->problem.SetLHS(&solution);
    current->problem.SetRHS(&rhs);
    if (current->klu->Solve() != 0)
      throw SolverError("triangular solves failed (KLU, background factors)");
  }


  void
  BackgroundFactorization::wait(LinearSolverStatistics &stats)
  {
    adopt(true, stats);
  }


  void
  BackgroundFactorization::reset()
  {
    if (running.valid())
      running.wait();
    running    = {};
    current    = nullptr;
    spare      = nullptr;
    up_to_date = false;
  }
} // namespace tissuefem::solvers
