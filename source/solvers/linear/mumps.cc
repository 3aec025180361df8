#include <tissuefem/base/input_error.h>
#include <tissuefem/base/timing.h>
#include <tissuefem/solvers/linear/interface.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Import.h>
#include <Epetra_Map.h>
#include <Epetra_MpiComm.h>
#include <Epetra_MultiVector.h>
#include <Epetra_Vector.h>
#include <dmumps_c.h>

#include <chrono>
#include <cmath>
#include <cstdint>

namespace tissuefem::solvers::linear
{
  namespace
  {
    /// MUMPS' 1-based control and information arrays.
    constexpr int
    at(const int fortran_index)
    {
      return fortran_index - 1;
    }


    /// Why a MUMPS phase failed, from INFOG(1) and INFOG(2).
    std::string
    mumps_failure(const DMUMPS_STRUC_C &id, const std::string &phase)
    {
      const int         code  = id.infog[at(1)];
      const std::string infog = "MUMPS INFOG(1) = " + std::to_string(code);
      if (code == -10)
        return "the matrix is numerically singular (" + infog + ")";
      if (code == -9 || code == -8 || code == -13 || code == -19)
        return "MUMPS ran out of memory in the " + phase + " (" + infog + ")";
      return "MUMPS failed in the " + phase + " (" + infog
             + ", INFOG(2) = " + std::to_string(id.infog[at(2)]) + ")";
    }


    /// A value in [-1, 1] that depends on the global index only, so that
    /// the symmetry test below decides alike on any number of processes.
    double
    probe_value(const long long index)
    {
      std::uint64_t h = static_cast<std::uint64_t>(index) + 0x9e3779b97f4a7c15;
      h               = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9;
      h               = (h ^ (h >> 27)) * 0x94d049bb133111eb;
      h ^= h >> 31;
      return 2. * static_cast<double>(h >> 11) / 9007199254740992. - 1.;
    }


    /// Calls @p f(k, local row, local column, value) for the k-th stored
    /// entry of the local rows of @p M, in storage order.
    template <typename Function>
    void
    for_each_stored_entry(const Epetra_CrsMatrix &M, const Function &f)
    {
      std::size_t k = 0;
      for (int row = 0; row < M.NumMyRows(); ++row)
        {
          int     n_entries = 0;
          double *values;
          int    *columns;
          M.ExtractMyRowView(row, n_entries, values, columns);
          for (int e = 0; e < n_entries; ++e, ++k)
            f(k, row, columns[e], values[e]);
        }
    }


    /**
     * Whether A equals its transpose to round-off: |A v - A^T v| <= 1e-10
     * |A v| (largest entries) for a pseudo-random v, two products instead
     * of a comparison entry by entry (which would need the rows of other
     * processes). A matrix that is not symmetric passes with probability
     * zero.
     */
    bool
    is_symmetric(const Epetra_CrsMatrix &A)
    {
      Epetra_Vector v(A.DomainMap()), Av(A.RangeMap()), ATv(A.DomainMap());
      for (int i = 0; i < v.MyLength(); ++i)
        v[i] = probe_value(A.DomainMap().GID64(i));
      A.Multiply(false, v, Av);
      A.Multiply(true, v, ATv);
      double scale = 0, difference = 0;
      Av.NormInf(&scale);
      Av.Update(-1., ATv, 1.);
      Av.NormInf(&difference);
      return difference <= 1e-10 * scale;
    }


    /// Whether a diagonal entry of @p A is zero on some process: a
    /// saddle-point system (the nodal dilatation's pressure rows), which L
    /// U can only factor by pivoting off the diagonal anyway.
    bool
    has_zero_diagonal(const Epetra_CrsMatrix &A)
    {
      Epetra_Vector diagonal(A.RowMap());
      A.ExtractDiagonalCopy(diagonal);
      int zero = 0;
      for (int i = 0; i < diagonal.MyLength() && zero == 0; ++i)
        zero = diagonal[i] == 0 ? 1 : 0;
      int anywhere = 0;
      A.Comm().MaxAll(&zero, &anywhere, 1);
      return anywhere == 1;
    }


    /**
     * MUMPS called directly (not through Amesos, which always asks it for
     * an unsymmetric LU): where the matrix is symmetric (as backward
     * Euler's, the quasistatic, the linearly implicit Euler's and the
     * nodal dilatation's saddle-point systems are, without friction) it
     * may be factorized as L D L^T with 1x1 and 2x2 pivots (MUMPS SYM = 2:
     * symmetric indefinite), on the benchmark scenes 5-28 % less solve
     * time and 4-10 % less memory than L U (doc/studies.md, MUMPS L D
     * L^T): by default for saddle-point systems (a zero on the diagonal),
     * for every symmetric matrix if asked; otherwise as L U. The matrix is
     * given distributed as it is (ICNTL(18) = 3), the right-hand side and
     * solution gathered on process 0. The symbolic analysis is kept across
     * Newton iterations and steps, and made again only when the matrix stops or
     * starts being symmetric (friction that begins to slip). MUMPS: Amestoy et
     * al. 2001 and its users' guide (doc/references.md).
     */
    class Mumps : public Interface
    {
    public:
      explicit Mumps(ParameterHandler &prm)
      {
        prm.enter_subsection("Linear solver");
        const std::string mode = prm.get("MUMPS symmetric factorization");
        symmetric_when         = mode == "true"    ? When::symmetric
                                 : mode == "false" ? When::never
                                                   : When::saddle_point;
        prm.leave_subsection();
      }

      ~Mumps() override
      {
        terminate();
      }

      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.enter_subsection("Linear solver");
        prm.declare_entry(
          "MUMPS symmetric factorization",
          "automatic",
          Patterns::Selection("automatic|true|false"),
          "For Type = MUMPS (or direct). true: a symmetric matrix (checked "
          "before each factorization: |A v - A^T v| <= 1e-10 |A v| for a "
          "pseudo-random v) is factorized as L D L^T with 1x1 and 2x2 "
          "pivots, any other as L U; measured 5-28 % less solve time and "
          "4-10 % less memory on 7,500-12,000 unknowns "
          "(benchmarks/symmetric_factorization.sh). automatic: L D L^T "
          "only for symmetric matrices with a zero on the diagonal "
          "(saddle-point systems: the nodal dilatation's; 11-21 % less "
          "solve time and 7-15 % less step time on a 9,600-tetrahedra "
          "box, benchmarks/nodal_dilatation_cost.sh), L U for the others: on "
          "crushed tetrahedra with self contact the recovery depends on "
          "round-off in Newton's path, and with L D L^T 32 of 33 starts "
          "untangled at the automatic pressure against 33 with L U "
          "(doc/tests.md). false: always L U.");
        prm.leave_subsection();
      }

      bool
      direct() const override
      {
        return true;
      }

      void
      reset() override
      {
        terminate();
      }

      void
      solve(const MatrixType &A,
            VectorType       &x,
            const VectorType &b,
            const bool        refactorize,
            const double /*relative_tolerance*/,
            LinearSolverStatistics &stats) override
      {
        const Epetra_CrsMatrix &M = A.trilinos_matrix();
        if (initialized && M.NumMyNonzeros() != n_local_nonzeros)
          terminate();
        if (refactorize || !factorized)
          factorize(M, stats);

        Epetra_MultiVector root(*root_map, 1);
        root.Import(b.trilinos_vector(), *to_root, Insert);
        id.icntl[at(20)] = 0; // dense right-hand side on process 0
        id.icntl[at(21)] = 0; // the solution there too
        id.nrhs          = 1;
        id.lrhs          = id.n;
        id.rhs           = root.MyLength() > 0 ? root[0] : nullptr;
        call(3, "solve");
        x.trilinos_vector().Import(root, *from_root, Insert);
      }

    private:
      void
      call(const int job, const std::string &phase)
      {
        id.job = job;
        dmumps_c(&id);
        if (id.infog[at(1)] < 0)
          throw SolverError(mumps_failure(id, phase));
      }

      /// A numeric factorization, preceded by the analysis where none is
      /// kept for the matrix's layout and symmetry.
      void
      factorize(const Epetra_CrsMatrix &M, LinearSolverStatistics &stats)
      {
        const auto start = std::chrono::steady_clock::now();
        factorized       = false;
        const bool symmetric_now
          = symmetric_when != When::never
            && (symmetric_when == When::symmetric || has_zero_diagonal(M))
            && is_symmetric(M);
        if (!initialized || symmetric_now != symmetric)
          {
            terminate();
            analyse(M, symmetric_now);
            ++stats.setups;
            stats.setup_seconds += seconds_since(start);
          }
        for_each_stored_entry(
          M, [&](const std::size_t k, int, int, const double value) {
            if (position[k] != not_given)
              values[position[k]] = value;
          });
        // MUMPS estimates its working memory in the analysis; pivoting can
        // need more: allow twice, then four times the estimate.
        for (int relaxation : {20, 100, 300})
          {
            id.icntl[at(14)] = relaxation;
            id.job           = 2;
            dmumps_c(&id);
            if (id.infog[at(1)] != -9 && id.infog[at(1)] != -8)
              break;
          }
        if (id.infog[at(1)] < 0)
          throw SolverError(mumps_failure(id, "factorization"));
        factorized = true;
        ++stats.factorizations;
      }

      /// Hands MUMPS the pattern (for L D L^T its upper triangle) and makes
      /// the symbolic analysis.
      void
      analyse(const Epetra_CrsMatrix &M, const bool symmetric_matrix)
      {
        const auto &comm = dynamic_cast<const Epetra_MpiComm &>(M.Comm());
        id               = DMUMPS_STRUC_C{};
        id.comm_fortran  = static_cast<MUMPS_INT>(MPI_Comm_c2f(comm.Comm()));
        id.par           = 1;
        id.sym           = symmetric_matrix ? 2 : 0;
        id.job           = -1;
        dmumps_c(&id);
        initialized = true;
        symmetric   = symmetric_matrix;
        if (id.infog[at(1)] < 0)
          throw SolverError(mumps_failure(id, "initialization"));
        // Nothing printed by MUMPS: failures are reported from INFOG.
        for (int stream : {1, 2, 3})
          id.icntl[at(stream)] = -1;
        id.icntl[at(4)]  = 0;
        id.icntl[at(18)] = 3; // the matrix distributed by rows as it is

        AssertThrow(M.RowMap().MinAllGID64() == 0
                      && M.NumGlobalRows64() == M.RowMap().MaxAllGID64() + 1,
                    ExcMessage("MUMPS needs rows numbered 0 ... n-1"));
        id.n             = static_cast<MUMPS_INT>(M.NumGlobalRows64());
        n_local_nonzeros = M.NumMyNonzeros();
        rows.clear();
        columns.clear();
        position.assign(n_local_nonzeros, not_given);
        for_each_stored_entry(
          M, [&](const std::size_t k, const int row, const int column, double) {
            const long long i = M.RowMap().GID64(row);
            const long long j = M.ColMap().GID64(column);
            if (symmetric && j < i)
              return;
            position[k] = rows.size();
            rows.push_back(static_cast<MUMPS_INT>(i + 1));
            columns.push_back(static_cast<MUMPS_INT>(j + 1));
          });
        values.assign(rows.size(), 0.);
        id.nnz_loc = static_cast<MUMPS_INT8>(rows.size());
        id.irn_loc = rows.data();
        id.jcn_loc = columns.data();
        id.a_loc   = values.data();
        call(1, "analysis");

        const bool root = comm.MyPID() == 0;
        // A map of the same index type as the matrix's (Epetra refuses to
        // import between int and long long maps).
        const long long n_root = root ? M.NumGlobalRows64() : 0;
        if (M.RowMap().GlobalIndicesLongLong())
          root_map = std::make_unique<Epetra_Map>(M.NumGlobalRows64(),
                                                  static_cast<int>(n_root),
                                                  0LL,
                                                  M.Comm());
        else
          root_map = std::make_unique<Epetra_Map>(static_cast<int>(
                                                    M.NumGlobalRows64()),
                                                  static_cast<int>(n_root),
                                                  0,
                                                  M.Comm());
        to_root   = std::make_unique<Epetra_Import>(*root_map, M.RangeMap());
        from_root = std::make_unique<Epetra_Import>(M.DomainMap(), *root_map);
      }

      /// Frees MUMPS' instance (collective: every process calls it).
      void
      terminate()
      {
        if (initialized)
          {
            id.job = -2;
            dmumps_c(&id);
          }
        initialized = false;
        factorized  = false;
      }

      /// When a symmetric matrix is factorized as L D L^T.
      enum class When
      {
        never,
        saddle_point,
        symmetric
      } symmetric_when
        = When::saddle_point;
      DMUMPS_STRUC_C id{};
      bool           initialized      = false;
      bool           factorized       = false;
      bool           symmetric        = false;
      int            n_local_nonzeros = 0;
      /// The entries given to MUMPS (1-based global indices) and their
      /// values; for each stored entry of the local rows its index among
      /// them (not_given: below the diagonal of a symmetric matrix).
      static constexpr std::size_t   not_given = std::size_t(-1);
      std::vector<MUMPS_INT>         rows, columns;
      std::vector<double>            values;
      std::vector<std::size_t>       position;
      std::unique_ptr<Epetra_Map>    root_map;
      std::unique_ptr<Epetra_Import> to_root, from_root;
    };
  } // namespace


  TISSUEFEM_REGISTER_LINEAR_SOLVER(
    Mumps,
    "MUMPS",
    "parallel sparse direct solver (MUMPS), the robust choice for meshes up "
    "to some 10^5 unknowns: L U, or L D L^T for symmetric saddle-point "
    "systems (or every symmetric matrix, see 'MUMPS symmetric "
    "factorization'); the symbolic analysis is kept "
    "across iterations and steps.")

  namespace
  {
    const bool direct_is_mumps = [] {
      LinearSolverRegistry::instance().add_synonym("direct", "MUMPS");
      return true;
    }();
  } // namespace
} // namespace tissuefem::solvers::linear
