#include <tissuefem/time/implicit_one_step.h>

#include <sstream>

namespace tissuefem::time
{
  /**
   * Quasistatics (lecture notes eq 2.11): inertia is neglected, each step
   * solves f_int(u) = f_ext(t_{n+1}) with the boundary data at t_{n+1},
   * starting from the previous equilibrium. The reported velocity is the
   * difference quotient (u_{n+1} - u_n)/dt; the acceleration is zero.
   *
   * Load continuation. A step Newton cannot take is retried from the last
   * equilibrium with half its load increment, and so on down to 'Maximum
   * step halvings'. Where an expression names t (the loads' own, or
   * 'Load factor', which is t / End time by default here), half the step
   * is half the increment. Where the loads are constant in time (a file
   * that sets 'Load factor = 1' under gravity), the reference
   * configuration carries no load (factor 0 at t = 0), and a step from an
   * equilibrium at t_a carrying Lambda_a < lambda, of size H, lays a ramp
   *
   *   Lambda(t) = Lambda_a + (t - t_a) / H (lambda - Lambda_a),
   *
   * reaching lambda at t_a + H: the whole step takes the whole increment,
   * a halved one half of it, and the steps after a failure follow the
   * ramp as they would follow t / End time, regrowing as the step
   * controller allows. This is the load stepping of Abaqus's static steps
   * (automatic increments) and FEBio's load curves.
   */
  class Quasistatic : public ImplicitOneStep
  {
  public:
    explicit Quasistatic(const ParameterHandler &)
    {
    }

    static void
    declare_parameters(ParameterHandler &)
    {
    }

    /// Equilibria: no inertia, so no damping either.
    Capabilities
    capabilities() const override
    {
      Capabilities c;
      c.in_time      = false;
      c.begins_steps = c.penalty_contact = c.augmented_lagrangian = true;
      return c;
    }

    void
    initialize(Context &c, State &state) override
    {
      ImplicitOneStep::initialize(c, state);
      // The reference configuration carries no load.
      reached    = 0;
      ramp_start = ramp_end = ramp_factor = 0;
      if (constant_loads())
        c.solid.hold_load_factor(reached);
      else
        c.solid.hold_load_factor(std::nullopt);
    }

    /// The controller's scalars, the load factor carried and the ramp.
    std::vector<double>
    checkpoint_scalars() const override
    {
      auto scalars = ImplicitOneStep::checkpoint_scalars();
      scalars.insert(
        scalars.end(),
        {reached, double(continued_steps), ramp_start, ramp_end, ramp_factor});
      return scalars;
    }

    void
    restore_scalars(const std::vector<double> &scalars) override
    {
      ImplicitOneStep::restore_scalars(scalars);
      // A checkpoint written before load continuation: its last
      // equilibrium carried the whole load.
      const bool has  = scalars.size() >= 8;
      reached         = has ? scalars[3] : full_factor(State());
      continued_steps = has ? static_cast<unsigned int>(scalars[4]) : 0;
      ramp_start      = has ? scalars[5] : 0;
      ramp_end        = has ? scalars[6] : 0;
      ramp_factor     = has ? scalars[7] : 0;
      if (constant_loads())
        context->solid.hold_load_factor(reached);
    }

    std::string
    summary() const override
    {
      if (continued_steps == 0)
        return {};
      return "load continuation: " + std::to_string(continued_steps)
             + " steps carried part of the constant loads (a ramp to the "
               "whole load after a failed step)";
    }

  protected:
    double
    mass_coefficient(const double) const override
    {
      return 0.;
    }

    void
    predict(const State &old_state,
            const double h,
            VectorType  &u_tilde,
            VectorType  &initial_guess) const override
    {
      u_tilde       = old_state.u;
      initial_guess = old_state.u;
      // v is the last step's difference quotient: linear extrapolation.
      if (context->time.extrapolate)
        initial_guess.add(h, old_state.v);
    }

    std::string
    attempt(const State &state,
            const double h,
            State       &next,
            StepReport  &report) override
    {
      if (!constant_loads())
        return ImplicitOneStep::attempt(state, h, next, report);
      const double asked = full_factor(state);
      // A deficit at the start of a step lays the ramp to the whole load
      // at its end.
      if (reached != asked && state.time >= ramp_end)
        {
          ramp_start  = state.time;
          ramp_end    = state.time + requested_step;
          ramp_factor = reached;
        }
      const double t      = state.time + h;
      const double factor = t >= ramp_end
                              ? asked
                              : ramp_factor
                                  + (t - ramp_start) / (ramp_end - ramp_start)
                                      * (asked - ramp_factor);
      context->solid.hold_load_factor(factor);
      const std::string failure
        = ImplicitOneStep::attempt(state, h, next, report);
      if (failure.empty())
        {
          continued_steps += factor != asked;
          reached = factor;
        }
      else
        context->solid.hold_load_factor(reached);
      return failure;
    }

    void
    finish(const State &old_state,
           const VectorType &,
           const double h,
           State       &new_state) const override
    {
      new_state.v = new_state.u;
      new_state.v -= old_state.u;
      new_state.v /= h;
      new_state.a.reinit(new_state.u);
    }

    std::string
    halving_cannot_help(const State &state) const override
    {
      // Boundary data or a tool that move with t, loads that grow with it,
      // or a constant load not yet carried whole: a smaller step is a
      // smaller problem.
      if (context->solid.changes_with_time()
          || (constant_loads() && reached != full_factor(state)))
        return {};
      return "a smaller step cannot help: nothing in this quasistatic "
             "problem changes with time, and its loads (if any) are "
             "carried whole already, so every step is the same problem "
             "(ramp the prescribed displacements by naming t in 'Boundary "
             "conditions/Dirichlet')";
    }

    std::string
    last_equilibrium(const State &state) const override
    {
      std::ostringstream s;
      s << "; the last equilibrium is at t = " << state.time;
      // A factor that names t, or the share of constant loads carried;
      // not "load factor 1" where the loads' own expressions name t.
      const auto loads = context->solid.load_history();
      if (loads == solid::Operators::LoadHistory::constant)
        s << ", load factor " << reached << " of " << full_factor(state);
      else if (const auto lambda = context->solid.load_factor(state.time);
               lambda && loads != solid::Operators::LoadHistory::none)
        s << ", load factor " << *lambda;
      s << " (a limit point of the load, or a load step still too large)";
      return s.str();
    }

  private:
    bool
    constant_loads() const
    {
      return context->solid.load_history()
             == solid::Operators::LoadHistory::constant;
    }

    double
    full_factor(const State &state) const
    {
      return context->solid.load_factor_at(state.time);
    }

    /// The load factor the last equilibrium carries (constant loads).
    double       reached         = 0;
    unsigned int continued_steps = 0;
    /// The ramp of a continuation: from ramp_factor at t = ramp_start to
    /// the whole load at ramp_end.
    double ramp_start = 0, ramp_end = 0, ramp_factor = 0;
  };

  TISSUEFEM_REGISTER_INTEGRATOR(
    Quasistatic,
    "quasistatic",
    "equilibrium at every load step, inertia neglected (lecture notes "
    "section 2.4); a failed step is retried with half its load increment.")
} // namespace tissuefem::time
