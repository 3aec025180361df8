#include <deal.II/base/mpi.h>

#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_index_access.h>
#include <deal.II/lac/trilinos_precondition.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/timing.h>
#include <tissuefem/solvers/linear/interface.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace tissuefem::solvers::linear
{
  namespace
  {
    /**
     * Conjugate gradients preconditioned by Trilinos ML algebraic multigrid
     * whose near-null space is the rigid-body modes. The hierarchy is built
     * once and kept across Newton iterations and steps while it works: a
     * solve with the kept hierarchy may take 'AMG rebuild factor' times the
     * iterations of the first solve after its build, no more; then (or when
     * CG fails) it is rebuilt from the current matrix and the solve made
     * again. When a diagonal entry of the matrix has changed by more than
     * 'AMG diagonal change' since the build (a penalty contact engaging or
     * letting go), whether the kept hierarchy is tried first is learnt
     * from the last such tries: the first time, and for 1, 2, 4 or 8 such
     * solves after each failed try (doubling while tries keep failing),
     * it is rebuilt without the try. On SOFA's large beam a try fails while
     * the beam lands on its floor (each try 10 iterations spent) and
     * succeeds once it rests (5-9 iterations against a 360 ms build;
     * doc/studies.md). Needs a symmetric positive definite matrix.
     */
    class CgAmg : public Interface
    {
    public:
      explicit CgAmg(ParameterHandler &prm)
      {
        prm.enter_subsection("Linear solver");
        relative_tolerance = prm.get_double("Relative tolerance");
        max_iterations     = prm.get_integer("Maximum iterations");
        rebuild_factor     = prm.get_double("AMG rebuild factor");
        diagonal_change    = prm.get_double("AMG diagonal change");
        coarse_size        = prm.get_integer("AMG coarse size");
        prm.leave_subsection();
        require(relative_tolerance > 0,
                "Linear solver/Relative tolerance",
                "must be > 0");
      }

      static void
      declare_parameters(ParameterHandler &prm);

      bool
      direct() const override
      {
        return false;
      }

      bool
      uses_near_null_space() const override
      {
        return true;
      }

      void
      set_near_null_space(const std::vector<VectorType> &modes,
                          const unsigned int             components) override
      {
        mode_vectors     = modes;
        this->components = components;
        amg.reset();
        untried = 1;
        backoff = 1;
      }

      void
      reset() override
      {
        amg.reset();
        modes.reset();
        diagonal.clear();
        diagonal_at.clear();
        diagonal_column.clear();
        diagonal_of = nullptr;
        untried     = 1;
        backoff     = 1;
      }

      void
      solve(const MatrixType       &A,
            VectorType             &x,
            const VectorType       &b,
            const bool              refactorize,
            const double            relative_tolerance,
            LinearSolverStatistics &stats) override;

    private:
      void
      build_amg(const MatrixType &A, LinearSolverStatistics &stats);

      bool
      diagonal_moved(const MatrixType &A) const;

      void
      keep_diagonal(const Epetra_CrsMatrix &matrix);

      unsigned int
      cg_solve(const MatrixType  &A,
               VectorType        &x,
               const VectorType  &b,
               const double       tolerance,
               const unsigned int max_iterations);

      double       relative_tolerance;
      unsigned int max_iterations;
      double       rebuild_factor;
      double       diagonal_change;
      unsigned int coarse_size;

      std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg;
      std::unique_ptr<Epetra_MultiVector>                modes;
      std::vector<VectorType>                            mode_vectors;
      /// The matrix's diagonal at the build, owned rows in order, where
      /// it is in the matrix's values, and of which matrix.
      std::vector<double>     diagonal;
      std::vector<int>        diagonal_at, diagonal_column;
      const Epetra_CrsMatrix *diagonal_of          = nullptr;
      int                     diagonal_nonzeros    = 0;
      unsigned int            reference_iterations = 0;
      unsigned int            components           = 1;
      /// Solves with a moved diagonal still to rebuild without trying the
      /// kept hierarchy, and how many the next failed try sets.
      unsigned int untried = 1;
      unsigned int backoff = 1;
    };


    void
    CgAmg::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Linear solver");
      prm.declare_entry("Relative tolerance",
                        "1e-10",
                        Patterns::Double(0, 1),
                        "For 'cg amg': stop when |b - A x| <= tolerance |b| "
                        "(l2 norms). Newton's iterations in quasistatic and "
                        "backward Euler steps ask for min(0.1, 0.5 |R_k| / "
                        "|R_0|) instead where that is looser (Eisenstat and "
                        "Walker's inexact Newton: loose solves far from the "
                        "solution, tight ones near it); Newton's own "
                        "tolerances decide the accuracy. The linearly "
                        "implicit Euler starts CG from its predictor h v_n "
                        "instead of zero (the same test, fewer "
                        "iterations).");
      prm.declare_entry("Maximum iterations",
                        "1000",
                        Patterns::Integer(1),
                        "For 'cg amg': iteration limit per solve.");
      prm.declare_entry("AMG rebuild factor",
                        "2",
                        Patterns::Double(1),
                        "For 'cg amg': rebuild the multigrid hierarchy when a "
                        "solve would take more than this times the "
                        "iterations of the first solve after the last build "
                        "(or fails): CG with the kept hierarchy stops there, "
                        "and the solve is made again with a fresh one. 1 "
                        "rebuilds whenever iterations grow.");
      prm.declare_entry(
        "AMG diagonal change",
        "1.5",
        Patterns::Double(1),
        "For 'cg amg': a solve whose matrix has a diagonal entry grown or "
        "shrunk by more than this factor since the hierarchy's build (a "
        "penalty contact engaging or letting go: its nodes' entries 100 "
        "times larger or smaller) rebuilds the hierarchy without first "
        "trying the kept one the first time, and after each try that "
        "failed ('AMG rebuild factor') for the next 1, 2, 4 or 8 such "
        "solves (doubling while tries fail; one again after a kept try). "
        "On SOFA's large beam a try fails while the beam lands on its "
        "floor (10 CG iterations spent) and succeeds once it rests (5-9 "
        "iterations against a 360 ms build): rebuilding at every such "
        "solve made its 2 s run 17.7 s instead of 15.1 s (doc/studies.md). "
        "Without contact the diagonal drifts by at most 1.17 over 20 steps. "
        "Changes of the whole matrix are left to 'AMG rebuild factor'. "
        "Values above 1e300 turn the test off (every solve tries first).");
      prm.declare_entry(
        "AMG coarse size",
        "500",
        Patterns::Integer(1, 100000),
        "For 'cg amg': ML coarsens until a level has at most this many "
        "unknowns, and solves that level directly (KLU). With the six "
        "rigid-body modes each aggregate keeps six unknowns, so a coarse "
        "level is nearly dense (some 170 entries a row): deal.II's 2000 "
        "left a 1,362-unknown level on a 24,576-tetrahedra cube whose KLU "
        "factorization took 79 ms of a 140 ms build; with 500 (one more "
        "level) the quasistatic Newton solves of benchmarks/peer_fenics.py "
        "took 0.55 s instead of 0.77 s, the same CG iterations within 2 %; "
        "SOFA's small beam 0.5 ms lower in its median step and 2-4 ms "
        "higher at the 95th percentile (215 against 181 CG iterations over "
        "its first second), the large beam's hierarchy the same "
        "(doc/studies.md, AMG coarse size).");
      prm.leave_subsection();
    }


    void
    CgAmg::solve(const MatrixType &A,
                 VectorType       &x,
                 const VectorType &b,
                 const bool /*refactorize*/,
                 const double            forcing,
                 LinearSolverStatistics &stats)
    {
      const double tolerance   = std::max(relative_tolerance, forcing);
      const bool   moved       = amg && diagonal_moved(A);
      const bool   untried_now = moved && untried > 0;
      if (untried_now)
        --untried;
      if (!amg || untried_now)
        build_amg(A, stats);
      const bool trial = moved && !untried_now;
      // A kept hierarchy gets 'AMG rebuild factor' times the iterations of
      // its first solve, no more: a matrix that changed much (contact
      // engaging: measured 680-1000 iterations a step on SOFA's beam with
      // the hierarchy of the step before, 21 with a fresh one) is detected
      // at that cost instead of after the whole solve.
      const unsigned int cap
        = reference_iterations == 0
            ? max_iterations
            : std::min<unsigned int>(max_iterations,
                                     std::ceil(rebuild_factor
                                               * reference_iterations));
      // The caller's starting iterate, for the retry with a new hierarchy.
      const VectorType start(x);
      unsigned int     iterations = cg_solve(A, x, b, tolerance, cap);
      // A failed try with a moved diagonal skips the next 'backoff' tries,
      // a successful one makes the next failure skip one. A kept hierarchy
      // is measured against its build's diagonal: after a kept try the
      // next solves are tries too, and their failures, whatever moved the
      // matrix, count.
      const bool failed
        = iterations == std::numeric_limits<unsigned int>::max();
      if (trial)
        {
          untried = failed ? backoff : 0;
          backoff = failed ? std::min(2 * backoff, 8u) : 1;
        }
      if (failed)
        {
          stats.iterations += cap;
          x = start;
          build_amg(A, stats);
          iterations = cg_solve(A, x, b, tolerance, max_iterations);
        }
      if (iterations == std::numeric_limits<unsigned int>::max())
        throw SolverError("CG did not converge in "
                          + std::to_string(max_iterations)
                          + " iterations ('Linear solver/Maximum "
                            "iterations')");
      if (reference_iterations == 0)
        reference_iterations = std::max(iterations, 1u);
      stats.iterations += iterations;
    }


    /// The ML hierarchy for @p A, with the rigid-body modes as near-null
    /// space where they were given.
    void
    CgAmg::build_amg(const MatrixType &A, LinearSolverStatistics &stats)
    {
      const auto build_start = std::chrono::steady_clock::now();
      TrilinosWrappers::PreconditionAMG::AdditionalData data;
      data.elliptic              = true;
      data.smoother_sweeps       = 2;
      data.aggregation_threshold = 0.02;
      Teuchos::ParameterList              list;
      std::unique_ptr<Epetra_MultiVector> unused;
      data.set_parameters(list, unused, A.trilinos_matrix());
      list.set("coarse: max size", static_cast<int>(coarse_size));
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
      keep_diagonal(A.trilinos_matrix());
      reference_iterations = 0;
      ++stats.setups;
      stats.setup_seconds += seconds_since(build_start);
    }


    /// Whether an entry of @p A's diagonal is more than 'AMG diagonal
    /// change' times, or less than its inverse, the entry at the build, on
    /// any process. A zero entry at either time counts as changed unless both
    /// are zero.
    bool
    CgAmg::diagonal_moved(const MatrixType &A) const
    {
      if (diagonal_change > 1e300)
        return false;
      const Epetra_CrsMatrix &matrix = A.trilinos_matrix();
      int                    *offsets, *columns;
      double                 *values;
      // Where the compressed rows could not be read at the build, the test
      // is off on this process (the processes still decide together).
      bool moved
        = diagonal_of != nullptr
          && (&matrix != diagonal_of
              || matrix.NumMyNonzeros() != diagonal_nonzeros
              || matrix.NumMyRows() != static_cast<int>(diagonal.size())
              || matrix.ExtractCrsDataPointers(offsets, columns, values) != 0);
      for (unsigned int i = 0; diagonal_of && !moved && i < diagonal.size();
           ++i)
        {
          // Another layout at the same address (a matrix made anew) is a
          // new matrix.
          const int at = diagonal_at[i];
          if (at >= 0 && columns[at] != diagonal_column[i])
            {
              moved = true;
              break;
            }
          const double now  = at < 0 ? 0. : std::abs(values[at]);
          const double then = std::abs(diagonal[i]);
          moved = now > diagonal_change * then || then > diagonal_change * now;
        }
      return Utilities::MPI::logical_or(moved, parallel_tools::communicator());
    }


    /// Where @p matrix keeps its diagonal in its compressed rows (-1: a
    /// row without its diagonal entry), and the values there now: read
    /// at every solve through these positions, since Epetra's
    /// ExtractDiagonalCopy() looks each up through the maps (10 ms a call
    /// on SOFA's large beam's 58,000 rows, against a 25 ms CG iteration).
    void
    CgAmg::keep_diagonal(const Epetra_CrsMatrix &matrix)
    {
      diagonal.clear();
      diagonal_at.clear();
      diagonal_column.clear();
      diagonal_of       = nullptr;
      diagonal_nonzeros = matrix.NumMyNonzeros();
      int    *offsets, *columns;
      double *values;
      if (matrix.ExtractCrsDataPointers(offsets, columns, values) != 0)
        return;
      diagonal_of = &matrix;
      for (int i = 0; i < matrix.NumMyRows(); ++i)
        {
          const int own = matrix.ColMap().LID(
            TrilinosWrappers::global_row_index(matrix, i));
          int at = -1;
          for (int k = offsets[i]; k < offsets[i + 1]; ++k)
            if (columns[k] == own)
              at = k;
          diagonal_at.push_back(at);
          diagonal_column.push_back(own);
          diagonal.push_back(at < 0 ? 0. : values[at]);
        }
    }


    /// CG iterations to |b - A x| <= @p tolerance |b|, or the largest
    /// unsigned int if CG does not get there.
    unsigned int
    CgAmg::cg_solve(const MatrixType  &A,
                    VectorType        &x,
                    const VectorType  &b,
                    const double       tolerance,
                    const unsigned int max_iterations)
    {
      SolverControl        control(max_iterations, tolerance * b.l2_norm());
      SolverCG<VectorType> cg(control);
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
  } // namespace


  TISSUEFEM_REGISTER_LINEAR_SOLVER(
    CgAmg,
    "cg amg",
    "conjugate gradients with Trilinos ML algebraic multigrid (rigid-body "
    "modes as near-null space), kept across iterations and steps: the choice "
    "for large 3D meshes and several processes; needs a positive definite "
    "Jacobian (stable, non-inverted states).")
} // namespace tissuefem::solvers::linear
