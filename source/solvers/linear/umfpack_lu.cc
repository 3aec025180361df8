#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/base/timing.h>
#include <tissuefem/solvers/linear/interface.h>

#include <Epetra_CrsMatrix.h>
#include <umfpack.h>

#include <algorithm>
#include <chrono>

namespace tissuefem::solvers::linear
{
  namespace
  {
    /**
     * SuiteSparse's UMFPACK LU on the rows of a matrix held by one process:
     * the symbolic analysis once per layout, the numeric factorization when
     * asked for or missing.
     */
    class Umfpack : public Interface
    {
    public:
      explicit Umfpack(ParameterHandler &)
      {
        require(parallel_tools::n_processes() == 1,
                "Linear solver/Type",
                "'UMFPACK' runs on one MPI process only; use 'MUMPS' or "
                "'cg amg' with mpirun");
      }

      ~Umfpack() override
      {
        reset();
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
        if (numeric)
          umfpack_dl_free_numeric(&numeric);
        if (symbolic)
          umfpack_dl_free_symbolic(&symbolic);
        numeric = symbolic = nullptr;
      }

      void
      solve(const MatrixType &A,
            VectorType       &x,
            const VectorType &b,
            const bool        refactorize,
            const double /*relative_tolerance*/,
            LinearSolverStatistics &stats) override;

    private:
      void
      copy_rows(const Epetra_CrsMatrix &A);

      void                         *symbolic = nullptr;
      void                         *numeric  = nullptr;
      std::vector<SuiteSparse_long> Ap, Ai;
      std::vector<double>           Ax;
      /// Within-row positions, in column order, of the matrix entries:
      /// Ax[p] is the entry at position order[p] of its row.
      std::vector<int> order;
    };


    /// The serial matrix in compressed rows, which UMFPACK reads as
    /// compressed columns of the transpose. The pattern (sorted column
    /// indices) is built with the symbolic analysis; later calls only copy
    /// the values.
    void
    Umfpack::copy_rows(const Epetra_CrsMatrix &A)
    {
      const int n = A.NumMyRows();
      if (!symbolic)
        {
          Ap.assign(n + 1, 0);
          Ai.clear();
          order.clear();
          std::vector<std::pair<SuiteSparse_long, int>> row;
          for (int r = 0; r < n; ++r)
            {
              int     length;
              double *values;
              int    *columns;
              A.ExtractMyRowView(r, length, values, columns);
              row.resize(length);
              for (int k = 0; k < length; ++k)
                row[k] = {A.ColMap().GID(columns[k]), k};
              std::sort(row.begin(), row.end());
              for (const auto &[column, position] : row)
                {
                  Ai.push_back(column);
                  order.push_back(position);
                }
              Ap[r + 1] = Ai.size();
            }
        }
      Ax.resize(Ai.size());
      for (int r = 0; r < n; ++r)
        {
          int     length;
          double *values;
          int    *columns;
          A.ExtractMyRowView(r, length, values, columns);
          for (SuiteSparse_long p = Ap[r]; p < Ap[r + 1]; ++p)
            Ax[p] = values[order[p]];
        }
    }


    void
    Umfpack::solve(const MatrixType &A,
                   VectorType       &x,
                   const VectorType &b,
                   const bool        refactorize,
                   const double /*relative_tolerance*/,
                   LinearSolverStatistics &stats)
    {
      const auto start        = std::chrono::steady_clock::now();
      const bool with_numeric = refactorize || !numeric;
      if (with_numeric)
        copy_rows(A.trilinos_matrix());
      const SuiteSparse_long n = Ap.size() - 1;
      double                 control[UMFPACK_CONTROL];
      umfpack_dl_defaults(control);
      if (!symbolic)
        {
          if (umfpack_dl_symbolic(n,
                                  n,
                                  Ap.data(),
                                  Ai.data(),
                                  Ax.data(),
                                  &symbolic,
                                  control,
                                  nullptr)
              != UMFPACK_OK)
            throw SolverError("UMFPACK symbolic analysis failed");
          ++stats.setups;
          stats.setup_seconds += seconds_since(start);
        }
      if (with_numeric)
        {
          if (numeric)
            umfpack_dl_free_numeric(&numeric);
          const auto status = umfpack_dl_numeric(Ap.data(),
                                                 Ai.data(),
                                                 Ax.data(),
                                                 symbolic,
                                                 &numeric,
                                                 control,
                                                 nullptr);
          if (status == UMFPACK_WARNING_singular_matrix)
            throw SolverError("the matrix is singular (UMFPACK status 1)");
          if (status != UMFPACK_OK)
            throw SolverError("UMFPACK numeric factorization failed (status "
                              + std::to_string(status) + ")");
          ++stats.factorizations;
        }
      // The rows of A read as columns are A^T: solve its transpose.
      if (umfpack_dl_solve(UMFPACK_At,
                           Ap.data(),
                           Ai.data(),
                           Ax.data(),
                           x.trilinos_vector()[0],
                           b.trilinos_vector()[0],
                           numeric,
                           control,
                           nullptr)
          != UMFPACK_OK)
        throw SolverError("UMFPACK solve failed");
    }
  } // namespace


  TISSUEFEM_REGISTER_LINEAR_SOLVER(
    Umfpack,
    "UMFPACK",
    "SuiteSparse's sparse LU, one MPI process only; the symbolic analysis is "
    "kept across iterations and steps.")
} // namespace tissuefem::solvers::linear
