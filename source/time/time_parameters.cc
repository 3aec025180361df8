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
                      "12",
                      Patterns::Integer(0, 30),
                      "When Newton fails, the step is retried with half the "
                      "step size at most this many times before the run stops "
                      "with an error. 12 reaches 1/4096 of the step: a block "
                      "whose nodes lie within 1 % of a point or a line "
                      "(tests/unit/inversion_recovery_*) converges only "
                      "below about 1/1000 of dt = 0.02, where the mass term "
                      "outweighs the stiffness of its crushed elements; 6 "
                      "(1/64) was too few. After a successful reduced step the "
                      "step size grows back towards 'Time step' (by 2, or as "
                      "'Optimal Newton iterations' says), but never straight "
                      "back to a size that failed: it approaches the last "
                      "failed size geometrically (sqrt(h h_failed)), and that "
                      "memory fades by a factor 1.25 per successful step. "
                      "No step is tried below 'Time step' / 2^(this number), "
                      "however the step got small: a quasistatic run that "
                      "reaches a limit point of its load stops there and "
                      "reports the load factor it reached "
                      "(tests/solver_failure/limit_point_svk_1d.prm).");
    prm.declare_entry(
      "Optimal Newton iterations",
      "0",
      Patterns::Integer(0, 100),
      "Implicit one-step methods (quasistatic, fixed-step backward Euler): "
      "the Newton "
      "iterations per step the step controller aims at, as FEBio's automatic "
      "time stepper: after a step that took n iterations the next step is "
      "h sqrt(optimal/n), between h/2 and 2h and at most 'Time step'. Steps "
      "then shrink after hard steps and grow after easy ones, so step sizes "
      "(and, for dynamics, the answer) depend on the iteration counts. 0: "
      "every step is 'Time step' unless Newton fails.");
    prm.declare_entry(
      "Predictor",
      "previous state",
      Patterns::Selection("extrapolation|previous state"),
      "Newton's initial guess in implicit one-step methods: 'previous state' "
      "(quasistatic: u_n; backward Euler: u_n + h v_n), or 'extrapolation' "
      "from the previous steps (quasistatic: u_n + h v_n with v_n the last "
      "step's difference quotient, i.e. linear extrapolation of the load "
      "path; backward Euler: u_n + h v_n + h^2 a_n). Measured: extrapolation "
      "costs Newton iterations on nearly incompressible quasistatics (the "
      "extrapolated state violates the volume constraint at second order) "
      "and can lead backward Euler into another solution of a step's "
      "equations when a crushed body re-expands violently; it is therefore "
      "not the default.");
    prm.declare_entry("Real-time budget",
                      "0.0333333333",
                      Patterns::Double(),
                      "Wall-clock seconds one step may take in an interactive "
                      "loop (1/30 s: a visual frame; Jeffrey's report aims at "
                      "1/50 s); > 0. The end of a run reports the share of "
                      "steps within it. With 'Time step' equal to this, the "
                      "simulation keeps up with real time.");
    prm.declare_entry(
      "Rayleigh mass damping",
      "0",
      Patterns::Double(0),
      "alpha of Rayleigh damping, the damping force D v with D = alpha M + "
      "beta K (1/s if SI; >= 0; SOFA's rayleighMass, FEBio's and Abaqus's "
      "alpha). A mode of angular frequency omega is damped with the ratio "
      "zeta = alpha/(2 omega) + beta omega/2: the mass term damps slow motion "
      "(sagging, swinging), the stiffness term fast motion. Backward Euler "
      "and linearly implicit Euler only (the run is refused otherwise), "
      "which solve it with the step (time/implicit_one_step.h); 0 "
      "(default): none.");
    prm.declare_entry(
      "Rayleigh stiffness damping",
      "0",
      Patterns::Double(0),
      "beta of Rayleigh damping (s if SI; >= 0; SOFA's rayleighStiffness). "
      "The stiffness term of the damping force over a step from u_n to "
      "u_{n+1} is beta (f(u_{n+1}) - f(u_n))/dt, with f the internal and "
      "contact forces minus the loads at t_{n+1}: beta K v for a linear "
      "body, and for linearly implicit Euler exactly SOFA's beta K(u_n) "
      "v_{n+1}. Costs one residual evaluation per step (the linearly "
      "implicit Euler with fixed Dirichlet values takes it from its own "
      "residual and one mass product instead). 0 (default): none.");
    IntegratorRegistry::instance().declare_parameters(prm);
    prm.leave_subsection();
  }


  void
  TimeParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Time integration");
    integrator
      = IntegratorRegistry::instance().canonical(prm.get("Integrator"),
                                                 "Time integration/Integrator");
    end_time           = prm.get_double("End time");
    time_step          = prm.get_double("Time step");
    max_step_halvings  = prm.get_integer("Maximum step halvings");
    optimal_iterations = prm.get_integer("Optimal Newton iterations");
    extrapolate        = prm.get("Predictor") == "extrapolation";
    real_time_budget   = prm.get_double("Real-time budget");
    rayleigh_mass      = prm.get_double("Rayleigh mass damping");
    rayleigh_stiffness = prm.get_double("Rayleigh stiffness damping");
    prm.leave_subsection();
    require(std::isfinite(real_time_budget) && real_time_budget > 0,
            "Time integration/Real-time budget",
            "must be > 0 (seconds), got " + std::to_string(real_time_budget));
    require(std::isfinite(rayleigh_mass) && rayleigh_mass >= 0,
            "Time integration/Rayleigh mass damping",
            "must be finite and >= 0 (1/s), got "
              + std::to_string(rayleigh_mass));
    require(std::isfinite(rayleigh_stiffness) && rayleigh_stiffness >= 0,
            "Time integration/Rayleigh stiffness damping",
            "must be finite and >= 0 (s), got "
              + std::to_string(rayleigh_stiffness));
    require(std::isfinite(time_step) && time_step > 0,
            "Time integration/Time step",
            "must be > 0, got " + std::to_string(time_step));
    require(std::isfinite(end_time) && end_time > 0,
            "Time integration/End time",
            "must be > 0, got " + std::to_string(end_time));
  }
} // namespace tissuefem::time
