#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/solvers/linear_solver.h>

namespace tissuefem::solvers
{
  void
  LinearSolver::declare_parameters(ParameterHandler &prm)
  {
    const auto &registry = linear::LinearSolverRegistry::instance();
    prm.enter_subsection("Linear solver");
    prm.declare_entry("Type",
                      "direct",
                      Patterns::Selection(registry.selection_pattern()),
                      "How Newton's linear systems are solved. "
                        + registry.documentation());
    prm.leave_subsection();
    registry.declare_parameters(prm);
  }


  LinearSolver::LinearSolver(ParameterHandler &prm)
  {
    prm.enter_subsection("Linear solver");
    const std::string given = prm.get("Type");
    prm.leave_subsection();
    const auto &registry = linear::LinearSolverRegistry::instance();
    type                 = registry.canonical(given, "Linear solver/Type");
    method               = registry.create(type, prm);
  }


  std::unique_ptr<LinearSolver>
  LinearSolver::with_defaults(const std::string &type)
  {
    ParameterHandler prm;
    declare_parameters(prm);
    prm.enter_subsection("Linear solver");
    prm.set("Type", type);
    prm.leave_subsection();
    return std::make_unique<LinearSolver>(prm);
  }


  LinearSolver::~LinearSolver() = default;


  void
  LinearSolver::set_near_null_space(const std::vector<VectorType> &modes,
                                    const unsigned int             components)
  {
    method->set_near_null_space(modes, components);
  }


  void
  LinearSolver::reset()
  {
    matrix = nullptr;
    method->reset();
    if (background)
      background->reset();
  }


  void
  LinearSolver::factorize_in_background(const bool         on,
                                        const std::string &parameter)
  {
    if (!on)
      {
        background.reset();
        return;
      }
    require(type == "KLU",
            parameter,
            "needs 'Linear solver/Type = KLU' (the factorizing thread runs "
            "Amesos' KLU on a serial copy of the matrix), not '"
              + type + "'");
    require(Utilities::MPI::n_mpi_processes(parallel_tools::communicator())
              == 1,
            parameter,
            "needs one MPI process (the factorizing thread's copy of the "
            "matrix lives on a serial communicator)");
    if (!background)
      background = std::make_unique<BackgroundFactorization>();
  }


  void
  LinearSolver::wait_for_background()
  {
    if (background)
      background->wait(stats);
  }


  void
  LinearSolver::solve(const MatrixType &A,
                      VectorType       &x,
                      const VectorType &b,
                      const bool        refactorize,
                      const double      relative_tolerance,
                      const bool        from_guess)
  {
    // The methods start from x as they find it (linear::Interface::solve).
    if (!from_guess)
      x = 0;
    if (matrix != &A.trilinos_matrix())
      {
        reset();
        matrix = &A.trilinos_matrix();
      }
    ++stats.solves;
    std::string failure;
    try
      {
        if (background)
          background->solve(A, x, b, refactorize, stats);
        else
          method->solve(A, x, b, refactorize, relative_tolerance, stats);
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
        throw SolverError("linear solver (" + type + ") failed: " + failure);
      }
  }
} // namespace tissuefem::solvers
