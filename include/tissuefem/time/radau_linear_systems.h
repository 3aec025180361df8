#pragma once

#include <tissuefem/base/parallel.h>
#include <tissuefem/solvers/linear_solver.h>
#include <tissuefem/time/stiffness.h>

#include <memory>

namespace tissuefem::time
{
  using namespace dealii;

  /**
   * The two linear systems of Radau IIA's transformed simplified Newton
   * iteration (Hairer and Wanner IV.8; Jeffrey D.16-D.17) for the
   * first-order form u' = v, v' = (f_ext - f_int(u))/m - c v with lumped
   * mass m: ((gamma_hat/h) I - J) x = r (real) and (((alpha_hat + i
   * beta_hat)/h) I - J) z = r (complex), J = [0 I; -K/m -c]. Eliminating
   * the velocity leaves (K + s M) x_u = M (r_v + (sigma + c) r_u), s =
   * sigma (sigma + c), and x_v = sigma x_u - r_u; the complex system is
   * solved in its real 2n x 2n form [K + pM, -qM; qM, K + pM] (s = p + iq,
   * always with MUMPS: it is not symmetric). Without stiffness (the
   * simplified Jacobian) both are diagonal and nothing is assembled.
   */
  class RadauLinearSystems
  {
  public:
    RadauLinearSystems(const double damping,
                       const double gamma_hat,
                       const double alpha_hat,
                       const double beta_hat);

    /// For a new layout: the lumped mass, a mask (1 on free entries, 0 on
    /// constrained ones), and the solver for the real system.
    void
    reinit(const VectorType      &mass,
           const VectorType      &free,
           const bool             assembled,
           solvers::LinearSolver &real_solver);

    /// Builds the matrices for the step h from K: both, or the real one
    /// alone when @p with_complex is false (for a method that has only
    /// the real system, as a DIRK stage).
    void
    factorize(const Stiffness &stiffness,
              const double     step,
              const bool       with_complex = true);

    /// In place on (r_u, r_v).
    void
    solve_real(const double step, VectorType &ru, VectorType &rv);

    /// In place on (r_u, r_v) (real parts) and (s_u, s_v) (imaginary).
    void
    solve_complex(const double step,
                  VectorType  &ru,
                  VectorType  &rv,
                  VectorType  &su,
                  VectorType  &sv);

  private:
    const double            damping, gamma_hat, alpha_hat, beta_hat;
    const VectorType       *mass = nullptr, *free = nullptr;
    bool                    assembled   = true;
    solvers::LinearSolver  *real_solver = nullptr;
    types::global_dof_index n_dofs      = 0;
    IndexSet                doubled;
    MatrixType              real_matrix, complex_matrix;
    std::unique_ptr<solvers::LinearSolver> complex_solver;
    bool real_refactorize = true, complex_refactorize = true;
  };
} // namespace tissuefem::time
