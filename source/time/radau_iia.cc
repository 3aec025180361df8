#include <tissuefem/base/input_error.h>
#include <tissuefem/base/timing.h>
#include <tissuefem/time/radau_iia.h>

#include <algorithm>
#include <chrono>
#include <sstream>

namespace tissuefem::time
{
  RadauIIA::RadauIIA(ParameterHandler &prm)
  {
    prm.enter_subsection("Time integration");
    prm.enter_subsection("Radau IIA");
    const double damping = get_damping_ratio(prm);
    jacobian_kind        = prm.get("Jacobian");
    tolerances.parse_parameters(prm, "Time integration/Radau IIA/");
    adaptive   = prm.get_bool("Adaptive step");
    max_newton = prm.get_integer("Maximum Newton iterations");
    prm.leave_subsection();
    prm.leave_subsection();
    check_damping_ratio(damping, "Time integration/Radau IIA/");
    system    = std::make_unique<FirstOrderSystem>(damping, "Radau IIA");
    stiffness = std::make_unique<Stiffness>(jacobian_kind);
  }


  void
  RadauIIA::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Radau IIA");
    declare_damping_ratio(prm, first_order_damping_documentation);
    prm.declare_entry("Jacobian",
                      "analytical",
                      Patterns::Selection(Stiffness::choices()),
                      "The stiffness in the Newton matrix (Jeffrey "
                      "appendix E): analytical = the automatically "
                      "differentiated tangent; numerical = forward "
                      "differences of the internal force; simplified = "
                      "none (mass and damping only, never assembled).");
    ErrorTolerances::declare_parameters(prm);
    prm.declare_entry("Adaptive step",
                      "true",
                      Patterns::Bool(),
                      "Choose the Runge-Kutta step from the error "
                      "estimate; false takes steps of 'Time step' "
                      "(halved only when Newton fails), for order "
                      "studies.");
    prm.declare_entry("Maximum Newton iterations",
                      "7",
                      Patterns::Integer(1, 100),
                      "Simplified Newton iterations per Runge-Kutta step "
                      "before the step is retried with a smaller h.");
    prm.leave_subsection();
  }


  Interface::Capabilities
  RadauIIA::capabilities() const
  {
    Capabilities c;
    if (jacobian_kind == "numerical")
      c.whole_mesh_parameter = "Time integration/Radau IIA/Jacobian";
    return c;
  }


  void
  RadauIIA::initialize(Context &c, State &state)
  {
    context = &c;
    // Its stage systems are built from the Jacobian itself (Stiffness).
    c.solid.solve_only_through_operators(false, c.linear_solver);
    set_up_vectors(state.u);
    derivative(state.time, state.u, state.v, f0u, f0v);
    state.a = f0v;
    h       = c.time.time_step;
  }


  StepReport
  RadauIIA::advance(State &state, const double end_time)
  {
    StepReport   report;
    const auto   start = std::chrono::steady_clock::now();
    const double target
      = std::min(state.time + context->time.time_step, end_time);
    const double interval_start = state.time;
    report.substeps             = 0;
    while (target - state.time > 1e-12 * context->time.time_step)
      {
        if (!adaptive)
          h = std::min(h, context->time.time_step);
        double step = h;
        // Do not leave a sliver to the end of the interval.
        const bool clipped = state.time + 1.05 * step >= target;
        if (clipped)
          step = target - state.time;
        if (stiffness->assembled() && !jacobian_current)
          {
            const auto assembly_start = std::chrono::steady_clock::now();
            stiffness->evaluate(context->solid, state.u, state.time);
            report.assembly_seconds += seconds_since(assembly_start);
            ++report.jacobian_evaluations;
            jacobian_current = jacobian_fresh = true;
            factorized_step                   = 0;
          }
        const Attempt attempt = try_step(state, step);
        report.newton_iterations += attempt.newton_iterations;
        if (!attempt.converged || (adaptive && attempt.error >= 1.))
          {
            ++report.rejected_attempts;
            h = attempt.next_step;
            if (h < 1e-10 * context->time.time_step)
              throw SolverError(
                "Radau IIA: the Runge-Kutta step fell below 1e-10 times "
                "the time step at t = "
                + std::to_string(state.time)
                + " (Newton does not converge or the error estimate "
                  "stays above the tolerance)");
            // Newton failed with a Jacobian of an older state: refresh.
            if (!attempt.converged && !jacobian_fresh)
              jacobian_current = false;
            continue;
          }
        accept(state, step, report);
        ++report.substeps;
        step_sum += step;
        // A step cut short at the interval's end says nothing against
        // the step the controller had.
        if (!adaptive)
          h = context->time.time_step;
        else if (!clipped || attempt.next_step < step)
          h = attempt.next_step;
      }
    report.dt = target - interval_start;
    ++intervals;
    totals.newton_iterations += report.newton_iterations;
    totals.jacobian_evaluations += report.jacobian_evaluations;
    totals.substeps += report.substeps;
    totals.rejected_attempts += report.rejected_attempts;
    report.solve_seconds = seconds_since(start) - report.assembly_seconds;
    return report;
  }


  void
  RadauIIA::mesh_changed()
  {
    VectorType u;
    context->solid.initialize_vector(u);
    set_up_vectors(u);
    stiffness->reset();
    factorized_step  = 0;
    jacobian_current = false;
    have_polynomial  = false;
  }


  std::string
  RadauIIA::summary() const
  {
    std::ostringstream s;
    const double       n = std::max(intervals, 1u);
    s << "Radau IIA (" << jacobian_kind << " Jacobian): " << intervals
      << " intervals of 'Time step'; per interval: mean Runge-Kutta step "
      << (totals.substeps > 0 ? step_sum / totals.substeps : 0.)
      << " (time units), Runge-Kutta steps " << totals.substeps / n
      << ", rejected " << totals.rejected_attempts / n
      << ", Jacobian evaluations " << totals.jacobian_evaluations / n
      << ", Newton iterations " << totals.newton_iterations / n;
    return s.str();
  }


  TISSUEFEM_REGISTER_INTEGRATOR(
    RadauIIA,
    "Radau IIA",
    "the 3-stage Radau IIA implicit Runge-Kutta method (order 5, adaptive "
    "step; Jeffrey appendix D) with lumped mass and mass-proportional "
    "damping; analytical, numerical or simplified Jacobian.")

  // Files written before the name was cased as the method's.
  namespace
  {
    const bool radau_earlier_spelling = [] {
      IntegratorRegistry::instance().add_alias("radau iia", "Radau IIA");
      return true;
    }();
  } // namespace
} // namespace tissuefem::time
