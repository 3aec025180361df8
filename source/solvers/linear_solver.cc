#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/solvers/linear_solver.h>

namespace tissuefem::solvers
{
  void
  LinearSolverParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Linear solver");
    prm.declare_entry("Type",
                      "direct",
                      Patterns::Selection("direct|cg amg"),
                      "'direct': UMFPACK sparse LU (robust, default); 'cg "
                      "amg': conjugate gradients with Trilinos ML algebraic "
                      "multigrid (large 3D meshes; needs a positive definite "
                      "Jacobian).");
    prm.declare_entry("Relative tolerance",
                      "1e-10",
                      Patterns::Double(0, 1),
                      "For 'cg amg': stop when |b - A x| <= tolerance |b|.");
    prm.declare_entry("Maximum iterations",
                      "1000",
                      Patterns::Integer(1),
                      "For 'cg amg': iteration limit.");
    prm.leave_subsection();
  }


  void
  LinearSolverParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Linear solver");
    type               = prm.get("Type");
    relative_tolerance = prm.get_double("Relative tolerance");
    max_iterations     = prm.get_integer("Maximum iterations");
    prm.leave_subsection();
    require(relative_tolerance > 0,
            "Linear solver/Relative tolerance",
            "must be > 0");
  }


  LinearSolver::LinearSolver(const LinearSolverParameters &parameters)
      : parameters(parameters)
  {
  }


  void
  LinearSolver::set_constant_modes(const std::vector<std::vector<bool>> &modes)
  {
    constant_modes = modes;
  }


  void
  LinearSolver::solve(const SparseMatrix<double> &A,
                      Vector<double>             &x,
                      const Vector<double>       &b) const
  {
    try
      {
        if (parameters.type == "direct")
          {
            SparseDirectUMFPACK lu;
            lu.initialize(A);
            lu.vmult(x, b);
            return;
          }
        TrilinosWrappers::SparseMatrix trilinos_matrix;
        trilinos_matrix.reinit(A);
        TrilinosWrappers::PreconditionAMG::AdditionalData amg_data;
        amg_data.elliptic       = true;
        amg_data.constant_modes = constant_modes;
        TrilinosWrappers::PreconditionAMG amg;
        amg.initialize(trilinos_matrix, amg_data);
        SolverControl            control(parameters.max_iterations,
                              parameters.relative_tolerance * b.l2_norm());
        SolverCG<Vector<double>> cg(control);
        x = 0;
        cg.solve(A, x, b, amg);
      }
    catch (const ExceptionBase &e)
      {
        std::string reason = one_line_message(e);
        if (reason.size() > 160)
          reason = reason.substr(0, 157) + "...";
        throw SolverError("linear solver (" + parameters.type
                          + ") failed: " + reason);
      }
  }
} // namespace tissuefem::solvers
