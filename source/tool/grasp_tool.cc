#include <deal.II/base/utilities.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/base/timing.h>
#include <tissuefem/tool/grasp_tool.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace tissuefem::tool
{
  void
  ToolParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Tool");
    prm.declare_entry("Grasp point",
                      "",
                      Patterns::Anything(),
                      "Reference coordinates (comma separated) of the point "
                      "the tool grasps; empty: no tool.");
    prm.declare_entry("Grasp radius",
                      "0",
                      Patterns::Double(),
                      "Vertices within this distance of 'Grasp point' "
                      "(length units) are held; > 0 with a tool.");
    prm.declare_entry("Trajectory",
                      "0; 0; 0",
                      Patterns::Anything(),
                      "Displacement of the tool as muparser expressions of t "
                      "(one per coordinate, separated by ';'; length "
                      "units). The held vertices move by d(t) - d(grasp "
                      "time).");
    prm.declare_entry("Trajectory file",
                      "",
                      Patterns::Anything(),
                      "A CSV file of tool positions recorded from a device: "
                      "rows 't, x, y[, z]' (time and length units), times "
                      "increasing; a first line that is not numeric is a "
                      "header. Positions are interpolated linearly and held "
                      "beyond the ends; d(t) is the position minus the "
                      "first. Replaces 'Trajectory' when set.");
    prm.declare_entry("Grasp time",
                      "0",
                      Patterns::Double(),
                      "When the tool grasps (time units); it acts at the "
                      "start of the first step at or after it.");
    prm.declare_entry("Release time",
                      "1e30",
                      Patterns::Double(),
                      "When the tool lets go (time units), > 'Grasp time'.");
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
                      "-1: the tool follows 'Trajectory' or 'Trajectory "
                      "file'. Otherwise it follows a live client (a device "
                      "driver or game engine) connected over TCP to "
                      "127.0.0.1 at this port (0: any free port; the port "
                      "is printed and written to <Output directory>/"
                      "live_port): the client sends lines 't x y z' (time, "
                      "tool position; d(t) is the position minus the "
                      "first), tissuefem answers each with 't fx fy fz', "
                      "the force extrapolated to that time, and simulates "
                      "a step once positions cover its end. 'bye' or "
                      "closing the connection ends the run cleanly.");
    prm.declare_entry("Live timeout",
                      "5",
                      Patterns::Double(),
                      "Wall-clock seconds to wait for the live client to "
                      "connect or send; a silent client ends the run "
                      "cleanly with the outputs so far; > 0.");
    prm.declare_entry("Haptic budget",
                      "0.002",
                      Patterns::Double(),
                      "Wall-clock seconds one haptic update may take (1/500 "
                      "s); the end of a run reports the share within it.");
    prm.leave_subsection();
  }


  void
  ToolParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Tool");
    grasp_point     = prm.get("Grasp point");
    radius          = prm.get_double("Grasp radius");
    trajectory      = prm.get("Trajectory");
    trajectory_file = prm.get("Trajectory file");
    grasp_time      = prm.get_double("Grasp time");
    release_time    = prm.get_double("Release time");
    haptic_rate     = prm.get_double("Haptic rate");
    extrapolation   = prm.get("Force extrapolation");
    haptic_budget   = prm.get_double("Haptic budget");
    live_port       = prm.get_integer("Live port");
    live_timeout    = prm.get_double("Live timeout");
    prm.leave_subsection();
    enabled = !Utilities::trim(grasp_point).empty();
    if (!enabled)
      return;
    require(std::isfinite(radius) && radius > 0,
            "Tool/Grasp radius",
            "must be > 0 (length units) when 'Grasp point' is set");
    require(std::isfinite(grasp_time) && std::isfinite(release_time)
              && release_time > grasp_time,
            "Tool/Release time",
            "must be finite and later than 'Grasp time'");
    require(std::isfinite(haptic_rate) && haptic_rate > 0,
            "Tool/Haptic rate",
            "must be > 0 (updates per time unit)");
    require(std::isfinite(haptic_budget) && haptic_budget > 0,
            "Tool/Haptic budget",
            "must be > 0 (seconds)");
    require(std::isfinite(live_timeout) && live_timeout > 0,
            "Tool/Live timeout",
            "must be > 0 (seconds)");
  }


  template <int dim>
  GraspTool<dim>::GraspTool(const ToolParameters     &p,
                            const Triangulation<dim> &mesh)
      : parameters(p)
  {
    const auto coordinates
      = parse_numbers(p.grasp_point, "Parameter 'Tool/Grasp point'");
    require(coordinates.size() == dim,
            "Tool/Grasp point",
            "needs " + std::to_string(dim) + " coordinates, got "
              + std::to_string(coordinates.size()));
    for (unsigned int d = 0; d < dim; ++d)
      grasp_point[d] = coordinates[d];
    const auto &points = mesh.get_vertices();
    const auto &used   = mesh.get_used_vertices();
    for (unsigned int v = 0; v < points.size(); ++v)
      if (used[v] && points[v].distance(grasp_point) <= p.radius)
        vertices.push_back(v);
    require(!vertices.empty(),
            "Tool/Grasp radius",
            "holds no vertex: none lies within " + std::to_string(p.radius)
              + " of 'Grasp point'");

    if (p.live_port >= 0)
      {
        // Positions arrive during the run (synchronize()).
      }
    else if (!Utilities::trim(p.trajectory_file).empty())
      {
        table = TrajectoryTable<dim>::read(p.trajectory_file,
                                           "Tool/Trajectory file");
      }
    else
      {
        // One line naming the parameter for any syntax error (make_function
        // silences muparser's own report).
        trajectory = make_function<dim>(p.trajectory, dim, "Tool/Trajectory");
      }
    for (unsigned int d = 0; d < dim && p.live_port < 0; ++d)
      require(std::isfinite(displacement(p.grasp_time)[d]),
              "Tool/Trajectory",
              "is not finite at the grasp time");
    next_haptic_time = 0;
  }


  template <int dim>
  Tensor<1, dim>
  GraspTool<dim>::displacement(const double time) const
  {
    Tensor<1, dim> d;
    if (trajectory)
      {
        trajectory->set_time(time);
        for (unsigned int c = 0; c < dim; ++c)
          d[c] = trajectory->value(Point<dim>(), c);
        return d;
      }
    // Linear interpolation in the recorded positions, held at the ends; a
    // live tool is at its reference position until the first arrives.
    return table.position(time) - table.first();
  }


  template <int dim>
  bool
  GraspTool<dim>::due(const double time) const
  {
    const double eps = 1e-9 * std::max(1., std::abs(time));
    if (!holding && !released && time >= parameters.grasp_time - eps
        && time < parameters.release_time - eps)
      return true;
    return holding && time >= parameters.release_time - eps;
  }


  template <int dim>
  void
  GraspTool<dim>::act(const time::State &state, solid::Solid<dim> &solid)
  {
    if (!holding)
      {
        grasp_time_actual = state.time;
        const auto  start = displacement(state.time);
        const auto &traj  = *this;
        solid.hold(
          vertices,
          [&traj, start](const double t) {
            return traj.displacement(t) - start;
          },
          state.u);
        holding = true;
      }
    else
      {
        solid.release();
        holding  = false;
        released = true;
      }
  }


  template <int dim>
  void
  GraspTool<dim>::connect(const std::string &directory)
  {
    // Every process takes part in the link (it shares the positions).
    if (parameters.live_port >= 0)
      link = std::make_unique<LiveLink>(parameters.live_port,
                                        parameters.live_timeout,
                                        dim,
                                        1. / parameters.haptic_rate,
                                        directory + "/live_port");
  }


  template <int dim>
  Record<dim>
  GraspTool<dim>::record(const time::State &state, solid::Solid<dim> &solid)
  {
    const auto     values = solid.held_force(state.u, state.a, state.time);
    Tensor<1, dim> force;
    for (unsigned int d = 0; d < dim; ++d)
      force[d] = values[d];
    const Tensor<1, dim> position = displacement(state.time);
    Record<dim>          result;
    result.position = position;
    result.force    = force;
    result.engaged  = holding;
    max_force       = std::max(max_force, force.norm());

    // Haptic updates in (t_n, t_{n+1}], extrapolated from data up to t_n.
    if (last_time)
      {
        const double t0 = *last_time, t1 = state.time;
        const double period = 1. / parameters.haptic_rate;
        if (next_haptic_time <= t0)
          next_haptic_time = (std::floor(t0 / period) + 1) * period;
        for (; next_haptic_time <= t1 * (1 + 1e-12); next_haptic_time += period)
          {
            const double         tau      = next_haptic_time;
            const auto           start    = std::chrono::steady_clock::now();
            const Tensor<1, dim> estimate = extrapolated_force(tau);
            ++haptic_updates;
            if (seconds_since(start) <= parameters.haptic_budget)
              ++within_budget;
            const Tensor<1, dim> reference
              = last_force + (force - last_force) * ((tau - t0) / (t1 - t0));
            const double error = (estimate - reference).norm();
            max_error          = std::max(max_error, error);
            sum_error += error;
            result.haptic.push_back({tau, estimate, error});
          }
        // Update the rate and the secant stiffness (Broyden), unless the
        // tool grasped or let go in between (a jump, not a trend).
        if (holding && held_at_last_record)
          {
            rate                    = (force - last_force) / (t1 - t0);
            have_rate               = true;
            const Tensor<1, dim> dx = position - last_position;
            if (dx.norm_square() > 0)
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
    held_at_last_record = holding;
    last_time           = state.time;
    last_force          = force;
    last_position       = position;
    if (link)
      {
        // What the communication thread answers with until the next step
        // (as extrapolated_force()).
        LiveLink::ForceModel model;
        model.valid            = true;
        model.holding          = holding;
        model.time             = state.time;
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
    return result;
  }


  template <int dim>
  Tensor<1, dim>
  GraspTool<dim>::extrapolated_force(const double tau) const
  {
    if (!last_time || !holding)
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
  bool
  GraspTool<dim>::synchronize(const double time)
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
  GraspTool<dim>::live_end() const
  {
    return link && link->ended() ? link->reason() : std::string();
  }


  template <int dim>
  std::string
  GraspTool<dim>::summary() const
  {
    std::ostringstream s;
    s << "tool: " << vertices.size()
      << " vertices held; haptic: " << haptic_updates << " updates at "
      << parameters.haptic_rate << " per time unit, " << std::setprecision(3)
      << (haptic_updates ? 100. * within_budget / haptic_updates : 100.)
      << " % within the budget of " << parameters.haptic_budget
      << " s; extrapolation error ('" << parameters.extrapolation
      << "') against the simulated force: mean "
      << (haptic_updates ? sum_error / haptic_updates : 0.) << ", max "
      << max_error << " (force units; largest tool force " << max_force << ")";
    if (link)
      s << "\nlive client: " << link->samples << " positions received; "
        << link->report(last_time ? *last_time : 0.) << "; "
        << (link->ended() ? "session ended: " + link->reason()
                          : std::string("session open at the end"));
    return s.str();
  }

  template <int dim>
  void
  GraspTool<dim>::declare_parameters(ParameterHandler &prm)
  {
    ToolParameters::declare_parameters(prm);
  }


  template <int dim>
  std::unique_ptr<Interface<dim>>
  GraspTool<dim>::create(ParameterHandler &prm, const Triangulation<dim> &mesh)
  {
    ToolParameters parameters;
    parameters.parse_parameters(prm);
    if (!parameters.enabled)
      return nullptr;
    return std::make_unique<GraspTool<dim>>(parameters, mesh);
  }

  template class GraspTool<1>;
  template class GraspTool<2>;
  template class GraspTool<3>;

  TISSUEFEM_REGISTER_TOOL(GraspTool,
                          "grasp",
                          "holds the vertices near 'Tool/Grasp point' from "
                          "'Grasp time' to 'Release time' and moves them along "
                          "a trajectory or a live device's positions.")
} // namespace tissuefem::tool
