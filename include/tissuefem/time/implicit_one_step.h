#pragma once

#include <tissuefem/time/interface.h>

#include <limits>

namespace tissuefem::time
{
  /**
   * The common shape of one-step implicit methods whose step is the
   * nonlinear system
   *
   *   c M (u - u_tilde) + f_int(u) - f_ext(t_{n+1}) = 0
   *
   * for u = u_{n+1}, solved by Newton's method: a derived class supplies
   * c, u_tilde and the initial guess, and v, a once u is known. Unless
   * 'Lift boundary increments' is off, the guess is first improved by one
   * Newton iteration that carries the boundary motion of the step into the
   * body through the Jacobian. A step whose
   * Newton iteration fails is retried with half the step size, at most
   * 'Maximum step halvings' times. The next step size comes from
   * next_step_size(): back towards 'Time step' by factors of two (or as
   * 'Optimal Newton iterations' says), never straight back to a size that
   * just failed.
   */
  class ImplicitOneStep : public Interface
  {
  public:
    void
    initialize(Context &context, State &state) override;

    StepReport
    advance(State &state, const double end_time) override;

    bool
    checkpointable() const override
    {
      return true;
    }

    /// The step controller's memory: step size, last failed size, last
    /// iteration count.
    std::vector<double>
    checkpoint_scalars() const override
    {
      return {step_size, failed_step, double(last_iterations)};
    }

    void
    restore_scalars(const std::vector<double> &scalars) override
    {
      step_size       = scalars.at(0);
      failed_step     = scalars.at(1);
      last_iterations = static_cast<unsigned int>(scalars.at(2));
    }

    /// The kept factorization belongs to the old mesh.
    void
    mesh_changed() override
    {
      kept_coefficient = -1;
    }

  protected:
    /// The coefficient c of the mass term for step size @p h.
    virtual double
    mass_coefficient(const double h) const = 0;

    /// Fills u_tilde and the Newton initial guess from the state at t_n.
    virtual void
    predict(const State &old_state,
            const double h,
            VectorType  &u_tilde,
            VectorType  &initial_guess) const = 0;

    /// v_{n+1} and a_{n+1} from u_{n+1} (in @p new_state) and the old state.
    virtual void
    finish(const State      &old_state,
           const VectorType &u_tilde,
           const double      h,
           State            &new_state) const = 0;

    /// Backward Euler's rates for u_{n+1} in @p new_state: v_{n+1} =
    /// (u_{n+1} - u_n)/h and a_{n+1} = (u_{n+1} - u_tilde)/h^2 (problem
    /// session eqs 3-4), for the methods whose u_tilde is u_n + h v_n.
    static void
    backward_difference_rates(const State      &old_state,
                              const VectorType &u_tilde,
                              const double      h,
                              State            &new_state);

    /// Backward Euler's u_tilde = u_n + h v_n (problem session eq 4) and
    /// Newton's initial guess: u_tilde, plus h^2 a_n (a_{n+1} ~ a_n) with
    /// 'Extrapolate' (context's time parameters).
    void
    backward_euler_prediction(const State &old_state,
                              const double h,
                              VectorType  &u_tilde,
                              VectorType  &initial_guess) const;

    /// What every attempt begins with: @p next.u sized, predict() into
    /// u_tilde and @p next.u, the solid's step begun at @p state, the
    /// damping folded in (damp()). Returns the step's mass coefficient.
    double
    begin_attempt(const State &state, const double h, State &next);

    Context *context = nullptr;

    /**
     * One attempt at the step from @p state to t + @p h: predictor,
     * boundary lifting, Newton. On success @p next holds u, v, a at t + h
     * (constrained entries set) and the result is empty; otherwise it is
     * Newton's reason for failing. Iterations and times go into @p report.
     * Methods that solve the step's equations otherwise (linearly implicit
     * Euler) override it and keep the step halving and control of
     * advance().
     */
    virtual std::string
    attempt(const State &state,
            const double h,
            State       &next,
            StepReport  &report);

    /// One Newton iteration from the guess @p u (with u_tilde set) with
    /// the change of the prescribed values as inhomogeneous constraints of
    /// the update (Operators::implicit_residual_lifting), solved with a
    /// new factorization or, if not @p refactorize, the kept one. Returns
    /// the largest entry of the update (length units); throws SolverError,
    /// leaving @p u unchanged, if the guess cannot be evaluated or the
    /// system solved. An iterative solver starts from update_guess().
    /// Without @p jacobian_needed (a direct solver's kept factorization
    /// serves, and nothing after reads the Jacobian) the solid may leave
    /// it unassembled (Operators::implicit_residual_lifting).
    double
    lift_boundary_increment(const double mass_coefficient,
                            const double time,
                            VectorType  &u,
                            StepReport  &report,
                            const bool   refactorize     = true,
                            const bool   jacobian_needed = true);

    /// A predictor of lift_boundary_increment()'s update from @p u, for an
    /// iterative solver to start from; false (the default): none, start
    /// from zero.
    virtual bool
    update_guess(const VectorType &u, VectorType &update) const
    {
      (void)u;
      (void)update;
      return false;
    }

    /**
     * The step's boundary lifting ('Lift boundary increments'): one
     * Newton iteration from the guess @p u to t_new with the mass
     * coefficient @p c, kept where keep_better_guess() says so, and the
     * three-field cell @p unknowns (if any) moved with it. Returns the
     * motion (as lift_boundary_increment(); -1 if no lifting was made or
     * its Jacobian does not belong to the state Newton starts from).
     */
    double
    lift(const double              c,
         const double              t_start,
         const double              t_new,
         VectorType               &u,
         StepReport               &report,
         solid::IterationUnknowns *unknowns);

    /// After lift_boundary_increment() moved @p guess to @p lifted (by
    /// @p motion): puts the guess with the new boundary values written in
    /// back into @p lifted where that has the lower energy. Returns the
    /// motion to report: @p motion if the lifting is kept, 0 if the guess
    /// is back and the lifting's Jacobian still belongs to it, -1 if not.
    double
    keep_better_guess(const VectorType &guess,
                      const double      mass_coefficient,
                      const double      time,
                      VectorType       &lifted,
                      const double      motion);

    /// Why a failed step of this method cannot be helped by a smaller
    /// one (then the run stops at once, saying so); empty if it can. A
    /// dynamic step's problem changes with its size, so the default is
    /// empty.
    virtual std::string
    halving_cannot_help(const State &state) const
    {
      (void)state;
      return {};
    }

    /// What the message of a run that gave up says of the last state
    /// reached, after "; " (empty: nothing).
    virtual std::string
    last_equilibrium(const State &state) const
    {
      (void)state;
      return {};
    }

    /**
     * Rayleigh damping D = alpha M + beta K ('Rayleigh mass damping',
     * 'Rayleigh stiffness damping'), for the methods whose velocity is
     * v_{n+1} = (u_{n+1} - u_n)/h (capabilities().rayleigh_damping). Their
     * damped step,
     *
     *   c M (u - u_tilde) + alpha/h M (u - u_n) + r(u) + beta/h (r(u) -
     *   r(u_n)) = 0,
     *
     * with r(u) = f_int(u) + contact - f_ext(t_{n+1}), is, divided by
     * kappa = 1 + beta/h,
     *
     *   c' M (u - u_tilde') + r(u) + g = 0,  c' = (c + alpha/h)/kappa,
     *   u_tilde' = (c u_tilde + alpha/h u_n)/(c + alpha/h),
     *   g = -beta/(h kappa) r(u_n):
     *
     * the undamped step with another mass coefficient and u_tilde and a
     * constant shift g, so that its Jacobian c' M + K has the form the
     * solid assembles and solves (doc/user_guide.md, "Rayleigh
     * damping"). Call after predict() and Operators::begin_step(): sets
     * u_tilde to u_tilde' (keeping u_tilde for finish(), see
     * rates_u_tilde()) and the shift (evaluating r(u_n)), and returns c'.
     * Without damping it returns @p c and changes nothing. With
     * @p from_lifting, for a step whose first solve is the boundary
     * lifting at u_n with unchanged prescribed values (the linearly
     * implicit Euler with fixed Dirichlet values), the shift is taken from
     * that lifting's residual instead, r(u_n) = R(u_n) - c' M (u_n -
     * u_tilde'): a mass product instead of a residual evaluation (17 of
     * 233 ms a step on SOFA's large beam).
     */
    double
    damp(const State &old_state,
         const double h,
         const double c,
         const double t_new,
         const bool   from_lifting = false);

    /// c' = (c + alpha/h) / (1 + beta/h), the damped step's mass
    /// coefficient for the undamped @p c and step @p h (see damp()).
    double
    damped_coefficient(const double c, const double h) const;

    /// The u_tilde of the undamped step (finish() takes it).
    const VectorType &
    rates_u_tilde() const
    {
      return damped ? undamped_u_tilde : u_tilde;
    }

    /// The energy the damping force took out over the step of size @p h
    /// from @p old_state to @p new_state, the last one attempted (energy
    /// units, from the step's equations: f_d = -c M (u - u_tilde) - r(u)
    /// on the free rows); 0 without damping. Called where a step is
    /// accepted, so that rejected attempts do not count.
    double
    damping_work(const State &old_state,
                 const State &new_state,
                 const double h);

    /// The solid's implicit residual (with @p with_jacobian, its Jacobian)
    /// plus the damping shift g.
    void
    residual(const VectorType &u,
             const double      c,
             const double      time,
             VectorType       &r,
             const bool        with_jacobian);

    /// The solid's implicit energy plus g . u (whose gradient is the shift).
    double
    energy(const VectorType &u, const double c, const double time);

    /// Tells the step controller how many iterations the step's solve
    /// took (what 'Optimal Newton iterations' weighs), for methods that
    /// override attempt().
    void
    record_iterations(const unsigned int iterations)
    {
      last_iterations = iterations;
    }

    /// The iterations last recorded (those of the previous solve).
    unsigned int
    recorded_iterations() const
    {
      return last_iterations;
    }

    /// u_tilde of the step being attempted (see predict()).
    VectorType u_tilde;

    /// The size of the step advance() is taking, before any halving.
    double requested_step = 0;

  private:
    /// The step controller (see 'Maximum step halvings', 'Optimal Newton
    /// iterations'): the size after a step of size @p h, @p reduced if
    /// attempts failed.
    double
    next_step_size(const double h, const bool reduced);

    /// The mass coefficient of the factorization the linear solver keeps
    /// for the next step's lifting (-1: none usable).
    double kept_coefficient = -1;
    /// Whether the step being attempted is damped, its undamped u_tilde
    /// and the shift g (damp()).
    bool       damped = false;
    VectorType undamped_u_tilde;
    VectorType shift;
    /// The factor -beta/(h kappa) of a shift still to be taken from the
    /// next lifting residual (0: none).
    double       deferred_shift  = 0;
    double       step_size       = 0;
    double       failed_step     = std::numeric_limits<double>::infinity();
    unsigned int last_iterations = 0;
  };
} // namespace tissuefem::time
