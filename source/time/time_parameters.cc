#include <tissuefem/base/input_error.h>
#include <tissuefem/time/interface.h>

#include <cmath>

namespace tissuefem::time
{
  void
  TimeParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Time integration");
    prm.declare_entry(
      "Integrator",
      "backward Euler",
      Patterns::Selection(IntegratorRegistry::instance().selection_pattern()),
      "How time advances. " + IntegratorRegistry::instance().documentation());
    prm.declare_entry("End time",
                      "1",
                      Patterns::Double(),
                      "Simulated time at which the run ends (s if SI); > 0.");
    prm.declare_entry("Time step",
                      "0.01",
                      Patterns::Double(),
                      "Step size dt (s if SI); > 0. For quasistatics it is the "
                      "load-step size in the time variable t of the "
                      "expressions.");
    prm.declare_entry("Maximum step halvings",
                      "6",
                      Patterns::Integer(0, 30),
                      "When Newton fails, the step is retried with half the "
                      "step size at most this many times before the run stops "
                      "with an error. After a successful reduced step the "
                      "step size doubles back towards 'Time step'.");
    prm.declare_entry("Real-time budget",
                      "0.0333333333",
                      Patterns::Double(),
                      "Wall-clock seconds one step may take in an interactive "
                      "loop (1/30 s: a visual frame; Jeffrey's report aims at "
                      "1/50 s); > 0. The end of a run reports the share of "
                      "steps within it. With 'Time step' equal to this, the "
                      "simulation keeps up with real time.");
    IntegratorRegistry::instance().declare_parameters(prm);
    prm.leave_subsection();
  }


  void
  TimeParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Time integration");
    integrator        = prm.get("Integrator");
    end_time          = prm.get_double("End time");
    time_step         = prm.get_double("Time step");
    max_step_halvings = prm.get_integer("Maximum step halvings");
    real_time_budget  = prm.get_double("Real-time budget");
    prm.leave_subsection();
    require(std::isfinite(real_time_budget) && real_time_budget > 0,
            "Time integration/Real-time budget",
            "must be > 0 (seconds), got " + std::to_string(real_time_budget));
    require(std::isfinite(time_step) && time_step > 0,
            "Time integration/Time step",
            "must be > 0, got " + std::to_string(time_step));
    require(std::isfinite(end_time) && end_time > 0,
            "Time integration/End time",
            "must be > 0, got " + std::to_string(end_time));
  }
} // namespace tissuefem::time
