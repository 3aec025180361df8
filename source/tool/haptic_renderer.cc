#include <tissuefem/base/input_error.h>
#include <tissuefem/base/timing.h>
#include <tissuefem/tool/haptic_renderer.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace tissuefem::tool
{
  void
  HapticParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Haptic rate",
                      "500",
                      Patterns::Double(),
                      "Force updates per unit time for the haptic device "
                      "(Hz if SI), written to haptic_force.csv; > 0.");
    prm.declare_entry("Force extrapolation",
                      "position",
                      Patterns::Selection("position|time"),
                      "How the haptic force is extrapolated between "
                      "simulation steps: 'position' = last force plus a "
                      "secant stiffness (estimated from the force and tool "
                      "position changes so far) times the tool's motion "
                      "since; 'time' = linear in time from the last two "
                      "steps.");
    prm.declare_entry("Live port",
                      "-1",
                      Patterns::Integer(-1, 65535),
                      "-1: the tool follows its trajectory. Otherwise it "
                      "follows a live client (a device driver or game "
                      "engine) connected over TCP to 127.0.0.1 at this port "
                      "(0: any free port; the port is printed and written "
                      "to <Output directory>/live_port): the client sends "
                      "lines 't x y z' (time, tool position; d(t) is the "
                      "position minus the first), tissuefem answers each "
                      "with 't fx fy fz', the force extrapolated to that "
                      "time, and simulates a step once positions cover its "
                      "end. A position beyond 'Live position limit' or "
                      "'Live jump limit' is answered 'refused t x y z: why' "
                      "and not followed. 'bye' or closing the connection "
                      "ends the run cleanly.");
    prm.declare_entry("Live timeout",
                      "5",
                      Patterns::Double(),
                      "Wall-clock seconds to wait for the live client to "
                      "connect or send; a silent client ends the run "
                      "cleanly with the outputs so far; > 0.");
    prm.declare_entry(
      "Live position limit",
      "0",
      Patterns::Double(0),
      "Live client: the farthest a position may lie from the client's first "
      "position (length units); a position beyond is refused (answered "
      "'refused ...', not followed: the tool keeps its last good target). "
      "Guards the run against a device glitch such as '0.1 1e308 0 0'. 0 "
      "(default): the diameter of the body.");
    prm.declare_entry(
      "Live jump limit",
      "0",
      Patterns::Double(0),
      "Live client: the farthest a position may lie from the last position "
      "followed (length units); a farther one is refused likewise. 0 "
      "(default): a tenth of the body's diameter (at 500 positions per "
      "second, 50 diameters per second).");
    prm.declare_entry(
      "Live reserved core",
      "true",
      Patterns::Bool(),
      "Live client: whether the simulation leaves one core to the thread "
      "that answers the client, using one thread fewer than the cores "
      "(when it would use them all). Measured on Jeffrey's muscle palpated "
      "live on two cores (doc/studies.md): the 99th percentile of the "
      "latency the client sees 1.3-1.6 ms with both cores simulating, "
      "0.19-0.27 ms with one left to the answers, the step median unchanged "
      "(one thread fewer made the palpation's steps at most 10 % longer).");
    prm.declare_entry("Haptic budget",
                      "0.002",
                      Patterns::Double(),
                      "Wall-clock seconds one haptic update may take (1/500 "
                      "s); the end of a run reports the share within it.");
  }


  void
  HapticParameters::parse_parameters(ParameterHandler  &prm,
                                     const std::string &section,
                                     const bool         check)
  {
    rate           = prm.get_double("Haptic rate");
    extrapolation  = prm.get("Force extrapolation");
    budget         = prm.get_double("Haptic budget");
    live_port      = prm.get_integer("Live port");
    live_timeout   = prm.get_double("Live timeout");
    position_limit = prm.get_double("Live position limit");
    jump_limit     = prm.get_double("Live jump limit");
    reserve_core   = prm.get_bool("Live reserved core");
    if (!check)
      return;
    require(std::isfinite(rate) && rate > 0,
            section + "/Haptic rate",
            "must be > 0 (updates per time unit)");
    require(std::isfinite(budget) && budget > 0,
            section + "/Haptic budget",
            "must be > 0 (seconds)");
    require(std::isfinite(live_timeout) && live_timeout > 0,
            section + "/Live timeout",
            "must be > 0 (seconds)");
    require(std::isfinite(position_limit) && position_limit >= 0,
            section + "/Live position limit",
            "must be finite and >= 0 (length units; 0: automatic)");
    require(std::isfinite(jump_limit) && jump_limit >= 0,
            section + "/Live jump limit",
            "must be finite and >= 0 (length units; 0: automatic)");
  }


  template <int dim>
  HapticRenderer<dim>::HapticRenderer(
    const HapticParameters                     &parameters,
    std::function<Tensor<1, dim>(const double)> displacement)
      : parameters(parameters)
      , displacement(std::move(displacement))
  {
  }


  template <int dim>
  void
  HapticRenderer<dim>::connect(const std::string &directory,
                               const double       body_diameter)
  {
    // Tool motions below a millionth of the body are round-off (a tool
    // held still by its trajectory's expression moves by 1e-18): the
    // secant stiffness must not learn from them.
    smallest_motion = 1e-6 * body_diameter;
    // Every process takes part in the link (it shares the positions).
    const LiveLink::Limits limits{
      parameters.position_limit > 0 ? parameters.position_limit : body_diameter,
      parameters.jump_limit > 0 ? parameters.jump_limit : 0.1 * body_diameter};
    if (live())
      link = std::make_unique<LiveLink>(parameters.live_port,
                                        parameters.live_timeout,
                                        dim,
                                        1. / parameters.rate,
                                        limits,
                                        directory + "/live_port",
                                        parameters.reserve_core);
  }


  template <int dim>
  bool
  HapticRenderer<dim>::synchronize(const double          time,
                                   TrajectoryTable<dim> &table)
  {
    if (!link)
      return true;
    const double eps = 1e-12 * std::max(1., std::abs(time));
    while (table.empty() || table.last_time() < time - eps)
      {
        if (link->ended())
          return false;
        // The link's thread has answered them already; out-of-order
        // positions are answered but not followed (append() drops them).
        for (const auto &sample : link->receive())
          {
            Tensor<1, dim> position;
            for (unsigned int d = 0; d < dim && d < sample.position.size(); ++d)
              position[d] = sample.position[d];
            table.append(sample.time, position);
          }
      }
    link->set_stepping(true);
    return true;
  }


  template <int dim>
  std::string
  HapticRenderer<dim>::live_end() const
  {
    return link && link->ended() ? link->reason() : std::string();
  }


  template <int dim>
  std::vector<typename Record<dim>::HapticSample>
  HapticRenderer<dim>::update(const double          time,
                              const Tensor<1, dim> &force,
                              const bool            engaged)
  {
    std::vector<typename Record<dim>::HapticSample> samples;
    const Tensor<1, dim> position = displacement(time);
    max_force                     = std::max(max_force, force.norm());
    // Haptic updates in (t_n, t_{n+1}], extrapolated from data up to t_n.
    if (last_time)
      {
        const double t0 = *last_time, t1 = time;
        const double period = 1. / parameters.rate;
        if (next_time <= t0)
          next_time = (std::floor(t0 / period) + 1) * period;
        for (; next_time <= t1 * (1 + 1e-12); next_time += period)
          {
            const double         tau      = next_time;
            const auto           start    = std::chrono::steady_clock::now();
            const Tensor<1, dim> estimate = extrapolated_force(tau, engaged);
            ++updates;
            if (seconds_since(start) <= parameters.budget)
              ++within_budget;
            const Tensor<1, dim> reference
              = last_force + (force - last_force) * ((tau - t0) / (t1 - t0));
            const double error = (estimate - reference).norm();
            max_error          = std::max(max_error, error);
            sum_error += error;
            samples.push_back({tau, estimate, error});
          }
        // The rate and the secant stiffness (Broyden), over steps at which
        // the tool stayed engaged.
        if (engaged && engaged_at_last)
          {
            rate      = (force - last_force) / (t1 - t0);
            have_rate = true;
            // Only from motions the body can feel: a force change over a
            // round-off motion (the tool held still while the tissue
            // relaxes) gave stiffnesses of 1e13 and extrapolated forces of
            // 1e11 on parameters/muscle_palpation.prm.
            const Tensor<1, dim> dx = position - last_position;
            if (dx.norm() > smallest_motion)
              stiffness
                += outer_product((force - last_force) - stiffness * dx, dx)
                   / dx.norm_square();
          }
        else
          {
            rate      = 0;
            have_rate = false;
            stiffness = 0;
          }
      }
    engaged_at_last = engaged;
    last_time       = time;
    last_force      = force;
    last_position   = position;
    if (link)
      {
        // What the communication thread answers with until the next step
        // (as extrapolated_force()).
        LiveLink::ForceModel model;
        model.valid            = true;
        model.holding          = engaged;
        model.time             = time;
        const bool by_position = parameters.extrapolation != "time";
        for (unsigned int i = 0; i < dim; ++i)
          {
            model.force.push_back(force[i]);
            model.position.push_back(position[i]);
            model.rate.push_back(!by_position && have_rate ? rate[i] : 0.);
            for (unsigned int j = 0; j < dim; ++j)
              model.stiffness.push_back(by_position ? stiffness[i][j] : 0.);
          }
        link->set_model(model);
        link->set_stepping(false);
      }
    return samples;
  }


  template <int dim>
  Tensor<1, dim>
  HapticRenderer<dim>::extrapolated_force(const double tau,
                                          const bool   engaged) const
  {
    if (!last_time || !engaged)
      return Tensor<1, dim>(); // nothing simulated yet, or let go
    Tensor<1, dim> estimate = last_force;
    if (parameters.extrapolation == "time")
      {
        if (have_rate)
          estimate += rate * (tau - *last_time);
      }
    else
      estimate += stiffness * (displacement(tau) - last_position);
    return estimate;
  }


  template <int dim>
  std::string
  HapticRenderer<dim>::summary() const
  {
    std::ostringstream s;
    s << "haptic: " << updates << " updates at " << parameters.rate
      << " per time unit, " << std::setprecision(3)
      << (updates ? 100. * within_budget / updates : 100.)
      << " % within the budget of " << parameters.budget
      << " s; extrapolation error ('" << parameters.extrapolation
      << "') against the simulated force: mean "
      << (updates ? sum_error / updates : 0.) << ", max " << max_error
      << " (force units; largest tool force " << max_force << ")";
    if (link)
      s << "\nlive client: " << link->samples << " positions received; "
        << link->report(last_time ? *last_time : 0.) << "; "
        << (link->ended() ? "session ended: " + link->reason()
                          : std::string("session open at the end"));
    return s.str();
  }

  template class HapticRenderer<1>;
  template class HapticRenderer<2>;
  template class HapticRenderer<3>;
} // namespace tissuefem::tool
