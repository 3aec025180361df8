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
#include <sstream>

namespace tissuefem::solvers::linear
{
  namespace
  {
    /// The integer after "INFOG(1) = " in what Amesos_Mumps wrote on a
    /// failure (captured: @p text), or "".
    std::string
    mumps_infog1(const std::string &text)
    {
      const auto at = text.find("INFOG(1) = ");
      if (at == std::string::npos)
        return "";
      std::istringstream value(text.substr(at + 11));
      long               code = 0;
      return value >> code ? std::to_string(code) : "";
    }

    /// Why Amesos' numeric factorization failed, from MUMPS' INFOG(1).
    std::string
    factorization_failure(const std::string &type, const std::string &infog1)
    {
      if (type != "MUMPS")
        return "the matrix is singular or too badly conditioned to factorize "
               "(KLU)";
      if (infog1 == "-10")
        return "the matrix is numerically singular (MUMPS INFOG(1) = -10)";
      if (infog1 == "-9" || infog1 == "-8" || infog1 == "-13")
        return "MUMPS ran out of memory (INFOG(1) = " + infog1 + ")";
      return "MUMPS failed (INFOG(1) = " + (infog1.empty() ? "?" : infog1)
             + ")";
    }


    /**
     * A sparse LU through Trilinos Amesos (MUMPS in parallel, or KLU on
     * the matrix gathered on one process): the symbolic analysis once per
     * matrix layout, kept across Newton iterations and steps; the numeric
     * factorization when asked for or missing.
     */
    class AmesosLU : public Interface
    {
    public:
      explicit AmesosLU(const std::string &type)
          : type(type)
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
              throw SolverError(
                factorization_failure(type, mumps_infog1(capture.text())));
            factorized = true;
            ++stats.factorizations;
          }
        const CerrCapture capture;
        if (amesos->Solve() != 0)
          throw SolverError("triangular solves failed (" + type + ")");
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
        amesos.reset(
          factory.Create(type == "MUMPS" ? "Amesos_Mumps" : "Amesos_Klu",
                         problem));
        if (!amesos)
          throw SolverError("Amesos has no " + type);
        // MUMPS prints nothing itself (its error, diagnostic and global
        // streams off); failures are reported by the codes it returns.
        Teuchos::ParameterList list;
        for (const char *stream : {"ICNTL(1)", "ICNTL(2)", "ICNTL(3)"})
          list.sublist("mumps").set(stream, -1);
        list.sublist("mumps").set("ICNTL(4)", 0);
        amesos->SetParameters(list);
        const CerrCapture capture;
        if (amesos->SymbolicFactorization() != 0)
          throw SolverError("symbolic factorization failed (" + type + ")");
        ++stats.setups;
        stats.setup_seconds += seconds_since(start);
      }

      const std::string                  type;
      Epetra_LinearProblem               problem;
      std::unique_ptr<Amesos_BaseSolver> amesos;
      bool                               factorized = false;
    };


    class Mumps : public AmesosLU
    {
    public:
      explicit Mumps(ParameterHandler &)
          : AmesosLU("MUMPS")
      {
      }
    };


    class Klu : public AmesosLU
    {
    public:
      explicit Klu(ParameterHandler &)
          : AmesosLU("KLU")
      {
      }
    };


    /// 'direct' is the default and means MUMPS.
    class Direct : public Mumps
    {
      using Mumps::Mumps;
    };
  } // namespace


  TISSUEFEM_REGISTER_LINEAR_SOLVER(
    Mumps,
    "MUMPS",
    "parallel sparse LU (Trilinos Amesos + MUMPS), the robust choice for "
    "meshes up to some 10^5 unknowns; the symbolic analysis is kept across "
    "iterations and steps.")
  TISSUEFEM_REGISTER_LINEAR_SOLVER(Direct, "direct", "the same as 'MUMPS'.")
  TISSUEFEM_REGISTER_LINEAR_SOLVER(
    Klu,
    "KLU",
    "Amesos' own sparse LU on the matrix gathered on one process (small "
    "meshes); the symbolic analysis is kept as for MUMPS.")
} // namespace tissuefem::solvers::linear
