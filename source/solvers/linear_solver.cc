#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>

#include <tissuefem/base/cerr_capture.h>
#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/base/timing.h>
#include <tissuefem/solvers/linear_solver.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_LinearProblem.h>
#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>
#include <umfpack.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

namespace tissuefem::solvers
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
  } // namespace


  void
  LinearSolverParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Linear solver");
    prm.declare_entry(
      "Type",
      "direct",
      Patterns::Selection("direct|MUMPS|KLU|UMFPACK|cg amg"),
      "How Newton's linear systems are solved. 'direct' or 'MUMPS': parallel "
      "sparse LU (Trilinos Amesos + MUMPS), the robust default for meshes up "
      "to some 10^5 unknowns. 'KLU': Amesos' own LU, gathered on one process "
      "(small meshes). 'UMFPACK': SuiteSparse's LU, one MPI process only. "
      "All three keep the symbolic analysis across iterations and steps. "
      "'cg amg': conjugate gradients with Trilinos ML algebraic multigrid "
      "(rigid-body modes as near-null space), kept across iterations and "
      "steps: the choice for large 3D meshes and several processes; needs a "
      "positive definite Jacobian (stable, non-inverted states).");
    prm.declare_entry("Relative tolerance",
                      "1e-10",
                      Patterns::Double(0, 1),
                      "For 'cg amg': stop when |b - A x| <= tolerance |b| "
                      "(l2 norms). Newton's iterations in quasistatic and "
                      "backward Euler steps ask for min(0.1, 0.5 |R_k| / "
                      "|R_0|) instead where that is looser (Eisenstat and "
                      "Walker's inexact Newton: loose solves far from the "
                      "solution, tight ones near it); Newton's own "
                      "tolerances decide the accuracy.");
    prm.declare_entry("Maximum iterations",
                      "1000",
                      Patterns::Integer(1),
                      "For 'cg amg': iteration limit per solve.");
    prm.declare_entry("AMG rebuild factor",
                      "2",
                      Patterns::Double(1),
                      "For 'cg amg': rebuild the multigrid hierarchy when a "
                      "solve would take more than this times the iterations "
                      "of the first solve after the last build (or fails): "
                      "CG with the kept hierarchy stops there, and the solve "
                      "is made again with a fresh one. 1 rebuilds whenever "
                      "iterations grow.");
    prm.leave_subsection();
  }


  void
  LinearSolverParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Linear solver");
    type               = prm.get("Type");
    relative_tolerance = prm.get_double("Relative tolerance");
    max_iterations     = prm.get_integer("Maximum iterations");
    rebuild_factor     = prm.get_double("AMG rebuild factor");
    prm.leave_subsection();
    if (type == "direct")
      type = "MUMPS";
    require(relative_tolerance > 0,
            "Linear solver/Relative tolerance",
            "must be > 0");
    require(type != "UMFPACK" || parallel_tools::n_processes() == 1,
            "Linear solver/Type",
            "'UMFPACK' runs on one MPI process only; use 'MUMPS' or 'cg amg' "
            "with mpirun");
  }


  /// The state each kind of solver keeps between solves.
  class LinearSolver::Implementation
  {
  public:
    // Which matrix object the kept analysis belongs to.
    const Epetra_CrsMatrix *matrix = nullptr;

    // Amesos (MUMPS, KLU).
    Epetra_LinearProblem               problem;
    std::unique_ptr<Amesos_BaseSolver> amesos;
    bool                               factorized = false;

    // UMFPACK.
    void                         *symbolic = nullptr;
    void                         *numeric  = nullptr;
    std::vector<SuiteSparse_long> Ap, Ai;
    std::vector<double>           Ax;

    // CG + AMG.
    std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg;
    std::unique_ptr<Epetra_MultiVector>                modes;
    std::vector<VectorType>                            mode_vectors;
    unsigned int                                       reference_iterations = 0;
    unsigned int                                       components           = 1;

    ~Implementation()
    {
      free_umfpack();
    }

    void
    free_umfpack()
    {
      if (numeric)
        umfpack_dl_free_numeric(&numeric);
      if (symbolic)
        umfpack_dl_free_symbolic(&symbolic);
      numeric = symbolic = nullptr;
    }

    /// Within-row positions, in column order, of the matrix entries:
    /// Ax[p] is the entry at position order[p] of its row.
    std::vector<int> order;

    /// The serial matrix in compressed rows, which UMFPACK reads as
    /// compressed columns of the transpose. The pattern (sorted column
    /// indices) is built with the symbolic analysis; later calls only copy
    /// the values.
    void
    copy_rows(const Epetra_CrsMatrix &A)
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

    using TimePoint = std::chrono::steady_clock::time_point;

    /// MUMPS or KLU (@p type) through Amesos: the symbolic analysis once
    /// per matrix, the numeric factorization when asked for or missing.
    /// @p start is when the solve began (setup time is counted from it).
    void
    solve_amesos(const std::string      &type,
                 Epetra_CrsMatrix       &M,
                 VectorType             &x,
                 const VectorType       &b,
                 const bool              refactorize,
                 const TimePoint         start,
                 LinearSolverStatistics &stats)
    {
      if (!amesos)
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

    /// UMFPACK on the rows of @p M: the symbolic analysis once, the
    /// numeric factorization when asked for or missing.
    void
    solve_umfpack(const Epetra_CrsMatrix &M,
                  VectorType             &x,
                  const VectorType       &b,
                  const bool              refactorize,
                  const TimePoint         start,
                  LinearSolverStatistics &stats)
    {
      const bool with_numeric = refactorize || !numeric;
      if (with_numeric)
        copy_rows(M);
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
            throw SolverError("UMFPACK numeric factorization failed "
                              "(status "
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

    /// CG with the kept AMG hierarchy (built on first use); a hierarchy
    /// that has become poor (or fails) is rebuilt from the current matrix
    /// and the solve repeated once.
    void
    solve_cg_amg(const MatrixType             &A,
                 const Epetra_CrsMatrix       &M,
                 VectorType                   &x,
                 const VectorType             &b,
                 const LinearSolverParameters &parameters,
                 const double                  relative_tolerance,
                 LinearSolverStatistics       &stats)
    {
      const double tolerance
        = std::max(parameters.relative_tolerance, relative_tolerance);
      if (!amg)
        build_amg(A, M, stats);
      // A kept hierarchy gets 'AMG rebuild factor' times the iterations of
      // its first solve, no more: a matrix that changed much (contact
      // engaging: measured 680-1000 iterations a step on SOFA's beam with
      // the hierarchy of the step before, 21 with a fresh one) is detected
      // at that cost instead of after the whole solve.
      const unsigned int cap
        = reference_iterations == 0
            ? parameters.max_iterations
            : std::min<unsigned int>(parameters.max_iterations,
                                     std::ceil(parameters.rebuild_factor
                                               * reference_iterations));
      unsigned int iterations = cg_solve(A, x, b, tolerance, cap);
      if (iterations == std::numeric_limits<unsigned int>::max())
        {
          stats.iterations += cap;
          build_amg(A, M, stats);
          iterations = cg_solve(A, x, b, tolerance, parameters.max_iterations);
        }
      if (iterations == std::numeric_limits<unsigned int>::max())
        throw SolverError("CG did not converge in "
                          + std::to_string(parameters.max_iterations)
                          + " iterations ('Linear solver/Maximum "
                            "iterations')");
      if (reference_iterations == 0)
        reference_iterations = std::max(iterations, 1u);
      stats.iterations += iterations;
    }

    /// The ML hierarchy for @p A, with the rigid-body modes as near-null
    /// space where they were given.
    void
    build_amg(const MatrixType       &A,
              const Epetra_CrsMatrix &M,
              LinearSolverStatistics &stats)
    {
      const auto build_start = std::chrono::steady_clock::now();
      TrilinosWrappers::PreconditionAMG::AdditionalData data;
      data.elliptic              = true;
      data.smoother_sweeps       = 2;
      data.aggregation_threshold = 0.02;
      Teuchos::ParameterList              list;
      std::unique_ptr<Epetra_MultiVector> unused;
      data.set_parameters(list, unused, M);
      if (!mode_vectors.empty())
        {
          const auto &map = mode_vectors[0].trilinos_vector().Map();
          modes
            = std::make_unique<Epetra_MultiVector>(map, mode_vectors.size());
          for (unsigned int m = 0; m < mode_vectors.size(); ++m)
            for (int i = 0; i < map.NumMyElements(); ++i)
              (*modes)[m][i] = mode_vectors[m].trilinos_vector()[0][i];
          list.set("null space: type", "pre-computed");
          list.set("null space: dimension",
                   static_cast<int>(mode_vectors.size()));
          list.set("null space: vectors", modes->Values());
          // ML aggregates nodes, not single dofs, when it knows how
          // many unknowns each node has.
          list.set("PDE equations", static_cast<int>(components));
        }
      amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
      amg->initialize(A, list);
      reference_iterations = 0;
      ++stats.setups;
      stats.setup_seconds += seconds_since(build_start);
    }

    /// CG iterations to |b - A x| <= @p tolerance |b|, or the largest
    /// unsigned int if CG does not get there.
    unsigned int
    cg_solve(const MatrixType  &A,
             VectorType        &x,
             const VectorType  &b,
             const double       tolerance,
             const unsigned int max_iterations)
    {
      SolverControl        control(max_iterations, tolerance * b.l2_norm());
      SolverCG<VectorType> cg(control);
      x = 0;
      try
        {
          cg.solve(A, x, b, *amg);
        }
      catch (const SolverControl::NoConvergence &)
        {
          return std::numeric_limits<unsigned int>::max();
        }
      return control.last_step();
    }
  };


  LinearSolver::LinearSolver(const LinearSolverParameters &parameters)
      : parameters(parameters)
      , implementation(std::make_unique<Implementation>())
  {
  }


  LinearSolver::~LinearSolver() = default;


  void
  LinearSolver::set_near_null_space(const std::vector<VectorType> &modes,
                                    const unsigned int             components)
  {
    implementation->mode_vectors = modes;
    implementation->components   = components;
    implementation->amg.reset();
  }


  void
  LinearSolver::reset()
  {
    implementation->matrix = nullptr;
    implementation->amesos.reset();
    implementation->factorized = false;
    implementation->free_umfpack();
    implementation->amg.reset();
    implementation->modes.reset();
  }


  void
  LinearSolver::solve(const MatrixType &A,
                      VectorType       &x,
                      const VectorType &b,
                      const bool        refactorize,
                      const double      relative_tolerance)
  {
    auto &impl = *implementation;
    auto &M    = const_cast<Epetra_CrsMatrix &>(A.trilinos_matrix());
    if (impl.matrix != &M)
      {
        reset();
        impl.matrix = &M;
      }
    ++stats.solves;
    const auto  start = std::chrono::steady_clock::now();
    std::string failure;
    try
      {
        if (parameters.type == "MUMPS" || parameters.type == "KLU")
          impl.solve_amesos(
            parameters.type, M, x, b, refactorize, start, stats);
        else if (parameters.type == "UMFPACK")
          impl.solve_umfpack(M, x, b, refactorize, start, stats);
        else
          impl.solve_cg_amg(A, M, x, b, parameters, relative_tolerance, stats);
      }
    catch (const SolverError &e)
      {
        failure = e.what();
      }
    catch (const ExceptionBase &e)
      {
        failure = one_line_message(e);
      }
    if (!failure.empty())
      {
        // A failed factorization or hierarchy is not kept.
        reset();
        if (failure.size() > 160)
          failure = failure.substr(0, 157) + "...";
        throw SolverError("linear solver (" + parameters.type
                          + ") failed: " + failure);
      }
  }
} // namespace tissuefem::solvers
