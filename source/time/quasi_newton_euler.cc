#include <tissuefem/base/input_error.h>
#include <tissuefem/solvers/lbfgs.h>
#include <tissuefem/time/implicit_one_step.h>

#include <algorithm>
#include <cmath>

namespace tissuefem::time
{
  /**
   * Backward Euler's step (problem session eqs 3-4),
   *
   *   M (u - u_tilde)/h^2 + f_int(u) - f_ext(t_{n+1}) = 0,  u_tilde = u_n +
   *   h v_n,
   *
   * solved by L-BFGS on the step's incremental potential instead of Newton
   * (Liu, Bouaziz and Kavan 2017, "Quasi-Newton methods for real-time
   * simulation of hyperelastic materials"): an iteration costs a residual,
   * an energy and a solve with a factorization kept across steps, never a
   * Jacobian assembly or factorization. Liu et al. prefactor a
   * Laplacian-like matrix of the rest state; here the initial Hessian is
   * the Jacobian M/h^2 + K that backward Euler's first iteration (the
   * boundary lifting) assembles and factorizes at the start of a step,
   * kept for the steps after it while it serves. It is made anew when
   * the step size or the mesh changes, when the previous step needed more
   * than 'Refresh iterations', when it is 'Refresh interval' steps old, and
   * when L-BFGS fails with an older one. The answer is backward Euler's to
   * Newton's tolerances ('Newton solver'); Rayleigh damping and penalty
   * contact enter through the step's residual and energy.
   */
  class QuasiNewtonEuler : public ImplicitOneStep
  {
  public:
    explicit QuasiNewtonEuler(ParameterHandler &prm)
    {
      prm.enter_subsection("Time integration");
      prm.enter_subsection("Quasi-Newton backward Euler");
      memory             = prm.get_integer("Memory");
      max_iterations     = prm.get_integer("Maximum iterations");
      refresh_iterations = prm.get_integer("Refresh iterations");
      refresh_interval   = prm.get_integer("Refresh interval");
      prm.leave_subsection();
      prm.leave_subsection();
    }

    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Quasi-Newton backward Euler");
      prm.declare_entry("Memory",
                        "5",
                        Patterns::Integer(0, 100),
                        "Correction pairs L-BFGS keeps (Liu et al. 2017 use "
                        "5); 0: every iteration solves with the kept "
                        "Hessian alone (modified Newton with a line "
                        "search).");
      prm.declare_entry("Maximum iterations",
                        "100",
                        Patterns::Integer(1, 10000),
                        "L-BFGS iterations per step with a fresh Hessian "
                        "before it gives up (then the step is halved); with "
                        "a kept one, twice 'Refresh iterations' at most "
                        "before it is made fresh.");
      prm.declare_entry("Refresh iterations",
                        "5",
                        Patterns::Integer(1, 10000),
                        "A step that needed more L-BFGS iterations than this "
                        "makes the next step factorize a fresh Hessian "
                        "(measured on SOFA's small beam, doc/studies.md: 3, "
                        "5 and 10 gave 67, 63 and 78 ms a step on average).");
      prm.declare_entry("Refresh interval",
                        "100",
                        Patterns::Integer(1, 100000),
                        "Steps one factorized Hessian serves at most; 1: a "
                        "fresh one every step (then each step costs "
                        "backward Euler's first Newton iteration plus the "
                        "L-BFGS iterations).");
      prm.leave_subsection();
    }

    void
    initialize(Context &c, State &state) override
    {
      require(c.solid.iteration_unknowns() == nullptr,
              "Materials/Mean dilatation/Update",
              "must not be 'three-field' with the quasi-Newton backward "
              "Euler (its cell unknowns need Newton's updates)");
      ImplicitOneStep::initialize(c, state);
      kept = -1;
    }

    Capabilities
    capabilities() const override
    {
      Capabilities c;
      c.begins_steps = c.penalty_contact = c.rayleigh_damping = true;
      return c;
    }

    /// The kept factorization is part of the state: a restarted run would
    /// make a fresh one and differ in the last digits.
    bool
    checkpointable() const override
    {
      return false;
    }

    void
    mesh_changed() override
    {
      ImplicitOneStep::mesh_changed();
      kept = -1;
    }

    std::string
    summary() const override
    {
      return "quasi-Newton backward Euler: " + std::to_string(refreshes)
             + " factorized Hessians over " + std::to_string(steps) + " steps";
    }

  protected:
    double
    mass_coefficient(const double h) const override
    {
      return 1. / (h * h);
    }

    void
    predict(const State &old_state,
            const double h,
            VectorType  &u_tilde,
            VectorType  &initial_guess) const override
    {
      backward_euler_prediction(old_state, h, u_tilde, initial_guess);
    }

    void
    finish(const State      &old_state,
           const VectorType &u_tilde,
           const double      h,
           State            &new_state) const override
    {
      backward_difference_rates(old_state, u_tilde, h, new_state);
    }

    std::string
    attempt(const State &state,
            const double h,
            State       &next,
            StepReport  &report) override
    {
      auto        &solid = context->solid;
      const double t_new = state.time + h;
      const double c     = begin_attempt(state, h, next);
      bool fresh = std::abs(c - kept) > 1e-12 * c || age + 1 >= refresh_interval
                   || recorded_iterations() > refresh_iterations;
      std::string failure;
      for (;; fresh = true)
        {
          VectorType u(next.u);
          failure = solve(c, t_new, fresh, u, report);
          if (failure.empty())
            {
              next.u.swap(u);
              break;
            }
          if (fresh)
            {
              kept = -1;
              return failure;
            }
        }
      ++steps;
      solid.apply_dirichlet_values(t_new, next.u);
      next.time = t_new;
      finish(state, rates_u_tilde(), h, next);
      return {};
    }

  private:
    /// L-BFGS from the guess @p u to the step's solution; with @p fresh,
    /// after the boundary lifting whose factorized Jacobian becomes the
    /// kept Hessian. Empty on success, else why it failed.
    std::string
    solve(const double c,
          const double t_new,
          const bool   fresh,
          VectorType  &u,
          StepReport  &report)
    {
      auto &solid = context->solid;
      if (fresh)
        {
          try
            {
              lift_boundary_increment(c, t_new, u, report, true);
            }
          catch (const SolverError &e)
            {
              return e.what();
            }
          kept = c;
          age  = 0;
          ++refreshes;
        }
      else
        ++age;
      solid.apply_dirichlet_values(t_new, u);
      // A kept Hessian gets twice 'Refresh iterations', no more: where it
      // no longer serves (measured: a floor first touched on SOFA's large
      // beam, 100 iterations before the retry with a fresh one), a fresh
      // one costs less than L-BFGS learning the change.
      const auto result = solvers::solve_lbfgs(
        context->newton,
        memory,
        fresh ? max_iterations
              : std::min(max_iterations, 2 * refresh_iterations),
        u,
        [&](const VectorType &x, VectorType &r) {
          residual(x, c, t_new, r, false);
        },
        [&](VectorType &z, const VectorType &q) {
          solid.solve_jacobian(context->linear_solver, z, q, false, 0.);
        },
        [&](const VectorType &x) { return energy(x, c, t_new); },
        solid.length_scale());
      report.newton_iterations += result.iterations;
      report.assembly_seconds += result.assembly_seconds;
      report.solve_seconds += result.solve_seconds;
      record_iterations(result.iterations);
      if (!result.residual_norms.empty())
        report.residual_norm = result.residual_norms.back();
      return result.converged ? std::string() : result.failure;
    }

    unsigned int memory = 5, max_iterations = 100, refresh_iterations = 5,
                 refresh_interval = 100;
    /// The mass coefficient of the kept factorization (-1: none) and its
    /// age in steps.
    double       kept = -1;
    unsigned int age  = 0;
    /// For the summary: factorizations made and steps taken.
    unsigned int refreshes = 0, steps = 0;
  };

  TISSUEFEM_REGISTER_INTEGRATOR(
    QuasiNewtonEuler,
    "quasi-Newton backward Euler",
    "backward Euler's step solved by L-BFGS on its incremental potential "
    "(Liu, Bouaziz and Kavan 2017) with a factorized Jacobian kept across "
    "steps as initial Hessian: the answer of backward Euler to Newton's "
    "tolerances, with residuals and back-substitutions instead of a "
    "Jacobian and a factorization per iteration.")
} // namespace tissuefem::time
