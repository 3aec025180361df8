#include <tissuefem/base/input_error.h>
#include <tissuefem/base/timing.h>
#include <tissuefem/time/implicit_one_step.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

namespace tissuefem::time
{
  /**
   * Linearly implicit (semi-implicit) Euler, Baraff and Witkin's "Large
   * steps in cloth simulation" (1998) and SOFA's EulerImplicitSolver:
   * backward Euler (problem session eqs 3-4) with the internal force
   * linearized about the start of the step,
   *
   *   f_int(u_{n+1}) ~ f_int(u_n) + K(u_n) (u_{n+1} - u_n),
   *
   * so that each step is one linear solve
   *
   *   (M/h^2 + K(u_n)) du = M v_n / h - f_int(u_n) + f_ext(t_{n+1}),
   *
   * u_{n+1} = u_n + du, v_{n+1} = du/h, a_{n+1} = (v_{n+1} - v_n)/h. This is
   * exactly the first Newton iteration of the backward Euler step started
   * from u_n, with the change of the prescribed displacements taken as
   * inhomogeneous constraints of du (Operators::implicit_residual_lifting).
   * The linearization error is O(|du|^2) = O(h^2) per step, so the method
   * stays first-order accurate, keeps backward Euler's stability for
   * linear problems, and costs one Jacobian, one factorization and one
   * solve per step, whatever the state: the cost of a step is known in
   * advance, which is what a real-time loop needs. Its answer differs from
   * converged backward Euler by the linearization error, which the studies
   * chart (parameters/studies/teran_2d.prm, muscle_choice.prm).
   *
   * A step whose system cannot be formed or solved (an element inverted at
   * u_n for a model that cannot represent it, a singular Jacobian), or that
   * lands in a state whose stored energy is not finite (an inverted
   * element), is retried with half the step, at most 'Maximum step
   * halvings' times, and the step grows back as for backward Euler
   * (ImplicitOneStep::advance()). The
   * statistics' residual column is 0: the residual at u_{n+1} is not
   * evaluated (that would cost a second assembly per step).
   */
  class LinearlyImplicitEuler : public ImplicitOneStep
  {
  public:
    explicit LinearlyImplicitEuler(ParameterHandler &prm)
    {
      prm.enter_subsection("Time integration");
      prm.enter_subsection("Linearly implicit Euler");
      interval   = prm.get_integer("Factorization interval");
      background = prm.get_bool("Background factorization");
      prm.leave_subsection();
      prm.leave_subsection();
    }

    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Linearly implicit Euler");
      prm.declare_entry(
        "Factorization interval",
        "1",
        Patterns::Integer(1, 1000),
        "Steps one factorization of M/h^2 + K serves. 1 (default): a new "
        "Jacobian and factorization every step (Baraff and Witkin's "
        "method). n > 1: the residual and the boundary lifting are still "
        "those of the step, but the solve reuses the factorization made up "
        "to n - 1 steps before (a W-method; first order still, with an "
        "error that grows with n and with how fast the stiffness changes), "
        "made anew at once when the step size or the constraints change "
        "or a step fails. A step then costs a residual and a "
        "back-substitution instead of a factorization: what steps at a "
        "haptic rate need. Runs with n > 1 cannot be checkpointed "
        "bit-identically.");
      prm.declare_entry(
        "Background factorization",
        "false",
        Patterns::Bool(),
        "Whether factorizations are made on a thread of its own, from a "
        "copy of the step's M/h^2 + K, while the steps go on solving with "
        "the last one finished (adopted at the first step after it "
        "finishes). One is asked for every 'Factorization interval'/2 "
        "steps (at least every step) and adopted at the latest when the "
        "next is asked for, so that the factors in use are at most "
        "'Factorization interval' - 1 steps old, as without it. No step "
        "then waits for a factorization except the first and those after a "
        "change of step size, constraints or mesh: the haptic loop's 95th "
        "percentile becomes a back-substitution's instead of a "
        "factorization's (doc/studies.md, 'Speed, measured'). "
        "Needs 'Factorization interval' of 2 or more, 'Linear solver/Type "
        "= KLU' and one MPI process; the answer "
        "depends on when the thread finishes (exact for a linear body, "
        "whose matrix does not change), so runs cannot be checkpointed.");
      prm.leave_subsection();
    }

    bool
    checkpointable() const override
    {
      return interval == 1 && !background;
    }

    void
    initialize(Context &c, State &state) override
    {
      ImplicitOneStep::initialize(c, state);
      // With an interval of 1 every step factorizes its own matrix; in the
      // background it would solve with the step's before.
      require(!background || interval >= 2,
              "Time integration/Linearly implicit Euler/Background "
              "factorization",
              "needs 'Factorization interval' of 2 or more (got 1: every "
              "step factorizes its own matrix)");
      c.linear_solver.factorize_in_background(
        background,
        "Time integration/Linearly implicit Euler/Background factorization");
    }

    /// Contact multipliers are not updated: one linear solve a step.
    Capabilities
    capabilities() const override
    {
      Capabilities c;
      c.begins_steps = c.penalty_contact = c.rayleigh_damping = true;
      return c;
    }

    void
    mesh_changed() override
    {
      ImplicitOneStep::mesh_changed();
      factorized_step = 0;
    }

  protected:
    double
    mass_coefficient(const double h) const override
    {
      return 1. / (h * h);
    }

    /// u_tilde = u_n + h v_n; the linearization point is u_n.
    void
    predict(const State &old_state,
            const double h,
            VectorType  &u_tilde,
            VectorType  &initial_guess) const override
    {
      u_tilde = old_state.u;
      u_tilde.add(h, old_state.v);
      initial_guess = old_state.u;
    }

    void
    finish(const State      &old_state,
           const VectorType &u_tilde,
           const double      h,
           State            &new_state) const override
    {
      backward_difference_rates(old_state, u_tilde, h, new_state);
    }

    /// One linear solve from @p state over @p h into @p next; empty on
    /// success, else why it failed (ImplicitOneStep::advance() then halves
    /// the step).
    std::string
    attempt(const State &state,
            const double h,
            State       &next,
            StepReport  &report) override
    {
      auto        &solid = context->solid;
      const double t_new = state.time + h;
      predict(state, h, u_tilde, next.u);
      double c = mass_coefficient(h);
      try
        {
          c = damp(state, h, c, t_new, boundary_fixed(state, t_new));
          // At u_n with its old prescribed values, one iteration with the
          // Jacobian M/h^2 + K(u_n); a kept factorization serves while it
          // is recent and of this step size (see 'Factorization interval').
          // In the background a factorization is asked for every
          // interval/2 steps: the one asked for before is adopted when the
          // next is (at the latest), so the factors in use are at most
          // 'Factorization interval' - 1 steps old, as without it. (Lags
          // of up to twice that made the muscle's swing after its release
          // unstable at dt = 2 ms, as a synchronous interval of 20 does.)
          const unsigned int period
            = background ? std::max(1u, interval / 2) : interval;
          const bool new_size = std::abs(h - factorized_step) > 1e-12 * h;
          const bool fresh    = new_size || age + 1 >= period;
          // Factors of another step size are no Jacobian of this step's:
          // a background factorization is then waited for (reset()
          // leaves none to solve with).
          if (background && new_size)
            context->linear_solver.reset();
          // Between factorizations a direct solver reads no matrix: the
          // step needs the residual only (the muscle at the haptic rate:
          // assembling the Jacobian made its assembly 2.0 ms of a 2.7 ms
          // step, against 0.44 ms without).
          lift_boundary_increment(c,
                                  t_new,
                                  next.u,
                                  report,
                                  fresh,
                                  fresh || !context->linear_solver.direct());
          age             = fresh ? 0 : age + 1;
          factorized_step = h;
        }
      catch (const SolverError &e)
        {
          factorized_step = 0;
          return e.what();
        }
      // The prescribed values (already reached up to round-off) and
      // hanging nodes set exactly.
      solid.apply_dirichlet_values(t_new, next.u);
      const char *failure
        = !std::isfinite(next.u.l2_norm()) ? "the update is not finite"
          : !std::isfinite(solid.stored_energy(next.u))
            ? "the step inverts an element (stored energy not finite)"
            : nullptr;
      if (failure)
        {
          factorized_step = 0;
          return failure;
        }
      next.time = t_new;
      finish(state, rates_u_tilde(), h, next);
      return {};
    }

    /// du = h v_n (u_tilde - u_n of the undamped step): the velocity
    /// kept over the step. Conjugate gradients started there need 40-45 %
    /// fewer iterations on SOFA's beams than from zero, for the same
    /// stopping test (doc/studies.md, "SOFA's benchmark beams").
    bool
    update_guess(const VectorType &u, VectorType &update) const override
    {
      update = rates_u_tilde();
      update -= u;
      return true;
    }

  private:
    /// Whether the prescribed values at @p t_new are those of @p state
    /// (then the step's lifting residual gives the damping's r(u_n)).
    bool
    boundary_fixed(const State &state, const double t_new) const
    {
      if (context->time.rayleigh_stiffness == 0)
        return false;
      VectorType prescribed(state.u);
      context->solid.apply_dirichlet_values(t_new, prescribed);
      prescribed -= state.u;
      return prescribed.linfty_norm() == 0;
    }

    /// 'Factorization interval'.
    unsigned int interval = 1;
    /// 'Background factorization'.
    bool background = false;
    /// The step size of the kept factorization (0: none usable) and the
    /// steps it has served since it was made.
    double       factorized_step = 0;
    unsigned int age             = 0;
  };

  TISSUEFEM_REGISTER_INTEGRATOR(
    LinearlyImplicitEuler,
    "linearly implicit Euler",
    "backward Euler with the internal force linearized at the start of each "
    "step (Baraff and Witkin 1998; SOFA's EulerImplicitSolver): one "
    "Jacobian and one linear solve per step, first-order accurate, stable "
    "at large steps; cheaper than backward Euler by its Newton iterations, "
    "less accurate by the linearization error.")
} // namespace tissuefem::time
