#include <tissuefem/base/cerr_capture.h>
#include <tissuefem/base/input_error.h>
#include <tissuefem/base/timing.h>
#include <tissuefem/solvers/linear/interface.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_LinearProblem.h>
#include <Teuchos_ParameterList.hpp>

#include <chrono>

namespace tissuefem::solvers::linear
{
  namespace
  {
    /**
     * Amesos' own sparse LU (KLU) on the matrix gathered on one process:
     * the symbolic analysis once per matrix layout, kept across Newton
     * iterations and steps; the numeric factorization when asked for or
     * missing.
     */
    class Klu : public Interface
    {
    public:
      explicit Klu(ParameterHandler &)
      {
      }

      static void
      declare_parameters(ParameterHandler &)
      {
      }

      bool
      direct() const override
      {
        return true;
      }

      void
      reset() override
      {
        amesos.reset();
        factorized = false;
      }

      void
      solve(const MatrixType &A,
            VectorType       &x,
            const VectorType &b,
            const bool        refactorize,
            const double /*relative_tolerance*/,
            LinearSolverStatistics &stats) override
      {
        const auto start = std::chrono::steady_clock::now();
        auto      &M     = const_cast<Epetra_CrsMatrix &>(A.trilinos_matrix());
        if (!amesos)
          analyse(M, start, stats);
        problem.SetLHS(&x.trilinos_vector());
        problem.SetRHS(const_cast<Epetra_MultiVector *>(
          static_cast<const Epetra_MultiVector *>(&b.trilinos_vector())));
        if (refactorize || !factorized)
          {
            factorized = false;
            const CerrCapture capture;
            if (amesos->NumericFactorization() != 0)
              throw SolverError("the matrix is singular or too badly "
                                "conditioned to factorize (KLU)");
            factorized = true;
            ++stats.factorizations;
          }
        const CerrCapture capture;
        if (amesos->Solve() != 0)
          throw SolverError("triangular solves failed (KLU)");
      }

    private:
      /// Creates the Amesos solver for @p M and makes its symbolic
      /// analysis.
      void
      analyse(Epetra_CrsMatrix                           &M,
              const std::chrono::steady_clock::time_point start,
              LinearSolverStatistics                     &stats)
      {
        problem.SetOperator(&M);
        Amesos factory;
        amesos.reset(factory.Create("Amesos_Klu", problem));
        if (!amesos)
          throw SolverError("Amesos has no KLU");
        // Later numeric factorizations of the same layout refactorize:
        // KLU reuses the pivot order of the last factorization with
        // pivoting (klu_refactor, no pivot search), and factorizes with
        // pivoting anew where the estimate min |u_ii| / max |u_ii| of the
        // result falls to 1e-12 or below (Amesos' RcondThreshold). The
        // Jacobians of successive steps and Newton iterations differ
        // little, so the old order stays stable; measured by
        // benchmarks/real_time_targets.sh at the haptic rate.
        Teuchos::ParameterList parameters;
        parameters.set("Refactorize", true);
        amesos->SetParameters(parameters);
        const CerrCapture capture;
        if (amesos->SymbolicFactorization() != 0)
          throw SolverError("symbolic factorization failed (KLU)");
        ++stats.setups;
        stats.setup_seconds += seconds_since(start);
      }

      Epetra_LinearProblem               problem;
      std::unique_ptr<Amesos_BaseSolver> amesos;
      bool                               factorized = false;
    };


  } // namespace


  TISSUEFEM_REGISTER_LINEAR_SOLVER(
    Klu,
    "KLU",
    "Amesos' own sparse LU on the matrix gathered on one process (small "
    "meshes); the symbolic analysis is kept as for MUMPS.")
} // namespace tissuefem::solvers::linear
