#include <tissuefem/base/input_error.h>
#include <tissuefem/time/error_norm.h>
#include <tissuefem/time/implicit_one_step.h>
#include <tissuefem/time/nodal.h>

#include <cmath>
#include <sstream>

namespace tissuefem::time
{
  /**
   * Backward Euler (problem session eqs 3-4): v_{n+1} = (u_{n+1} - u_n)/dt
   * and rho (v_{n+1} - v_n)/dt = div P + f at t_{n+1}. Dividing eq 4 by dt^2
   * gives c = 1/dt^2 and u_tilde = u_n + dt v_n; the acceleration is
   * a_{n+1} = (v_{n+1} - v_n)/dt = c (u_{n+1} - u_tilde). Unconditionally
   * stable and first-order accurate; it damps high frequencies.
   *
   * With 'Adaptive step' each call of advance() covers one 'Time step' (an
   * output interval) in steps h chosen from a local error estimate: the
   * difference between the backward Euler step and the trapezoidal
   * (second-order) step through the same end points,
   *   e_u = h/2 (v_{n+1} - v_n),   e_v = h/2 (a_{n+1} - a_n),
   * the leading term h^2/2 y'' of the local error of the first-order form
   * y = (u, v) (e_v from the second step on a mesh: a_n must be a backward
   * Euler acceleration, which the initial state does not have). A step with
   * weighted norm |e| > 1 is rejected; the next h is h * min(4, max(0.2, 0.9 /
   * sqrt(|e|))) (the estimate is O(h^2)).
   */
  class BackwardEuler : public ImplicitOneStep
  {
  public:
    explicit BackwardEuler(ParameterHandler &prm)
    {
      prm.enter_subsection("Time integration");
      prm.enter_subsection("Backward Euler");
      adaptive = prm.get_bool("Adaptive step");
      tolerances.parse_parameters(prm, "Time integration/Backward Euler/");
      prm.leave_subsection();
      prm.leave_subsection();
    }

    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Backward Euler");
      prm.declare_entry("Adaptive step",
                        "false",
                        Patterns::Bool(),
                        "false: steps of 'Time step', halved only when "
                        "Newton fails. true: each 'Time step' is an output "
                        "interval covered by steps chosen from the local "
                        "error estimate (backward Euler against the "
                        "trapezoidal rule) and the tolerances below.");
      ErrorTolerances::declare_parameters(prm, "1e-3", "1e-5", "1e-3");
      prm.leave_subsection();
    }

    Capabilities
    capabilities() const override
    {
      Capabilities c;
      c.begins_steps = c.penalty_contact = c.augmented_lagrangian = true;
      c.rayleigh_damping                                          = true;
      return c;
    }

    void
    initialize(Context &c, State &state) override
    {
      ImplicitOneStep::initialize(c, state);
      h = c.time.time_step;
      if (adaptive)
        set_up_error_control();
    }

    StepReport
    advance(State &state, const double end_time) override
    {
      if (!adaptive)
        return ImplicitOneStep::advance(state, end_time);
      auto        &linear_solver = context->linear_solver;
      const auto   linear_before = linear_solver.statistics().iterations;
      const double target
        = std::min(state.time + context->time.time_step, end_time);
      const double interval_start = state.time;
      StepReport   report;
      report.substeps = 0;
      State next;
      while (target - state.time > 1e-12 * context->time.time_step)
        {
          double step = std::min(h, context->time.time_step);
          // Do not leave a sliver to the end of the interval.
          if (state.time + 1.05 * step >= target)
            step = target - state.time;
          if (step < 1e-10 * context->time.time_step)
            throw SolverError(
              "backward Euler: the step fell below 1e-10 'Time step' at t = "
              + std::to_string(state.time)
              + " (tolerances too tight or the solution not smooth)");
          const std::string failure = attempt(state, step, next, report);
          if (!failure.empty())
            {
              ++report.rejected_attempts;
              h = step / 4;
              continue;
            }
          VectorType eu(next.v), ev(next.a);
          eu -= state.v;
          eu *= step / 2;
          ev -= state.a;
          ev *= step / 2;
          std::vector<const VectorType *> velocity_errors;
          if (have_acceleration)
            velocity_errors.push_back(&ev);
          const double error = std::max(
            tolerances.norm(
              {&eu}, velocity_errors, free, state.u, state.v, &next.u, &next.v),
            1e-10);
          h = step * std::min(4., std::max(0.2, 0.9 / std::sqrt(error)));
          if (error > 1.)
            {
              ++report.rejected_attempts;
              continue;
            }
          // Accepted: contributions with history commit it (a rejected
          // step's stick points and multipliers are dropped).
          context->solid.accept_step(next.u, next.time);
          report.damping_work += damping_work(state, next, step);
          state.time = next.time;
          state.u.swap(next.u);
          state.v.swap(next.v);
          state.a.swap(next.a);
          have_acceleration = true;
          ++report.substeps;
        }
      report.linear_iterations
        = linear_solver.statistics().iterations - linear_before;
      report.dt = target - interval_start;
      return report;
    }

    void
    mesh_changed() override
    {
      ImplicitOneStep::mesh_changed();
      if (adaptive)
        set_up_error_control();
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

    std::vector<double>
    checkpoint_scalars() const override
    {
      auto scalars = ImplicitOneStep::checkpoint_scalars();
      scalars.push_back(h);
      scalars.push_back(have_acceleration ? 1. : 0.);
      return scalars;
    }

    void
    restore_scalars(const std::vector<double> &scalars) override
    {
      ImplicitOneStep::restore_scalars(scalars);
      h                 = scalars.at(3);
      have_acceleration = scalars.at(4) != 0;
    }

  private:
    /// The free-entry mask for the current constraints; the next error
    /// estimate has no backward Euler acceleration yet.
    void
    set_up_error_control()
    {
      context->solid.initialize_vector(free);
      free = 1.;
      context->solid.zero_constrained_entries(free);
      have_acceleration = false;
    }

    bool            adaptive = false;
    ErrorTolerances tolerances;
    /// The step the error control proposes next.
    double h = 0;
    /// 1 on free entries, 0 on constrained ones.
    VectorType free;
    /// Whether state.a is a backward Euler acceleration (after the first
    /// step on a mesh), so that e_v can be formed; until then only e_u is
    /// controlled.
    bool have_acceleration = false;
  };

  TISSUEFEM_REGISTER_INTEGRATOR(
    BackwardEuler,
    "backward Euler",
    "implicit first-order dynamics (Teran problem "
    "session eqs 3-6), fixed step or adaptive from a local error estimate.")
} // namespace tissuefem::time
