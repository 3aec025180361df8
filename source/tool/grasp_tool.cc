#include <deal.II/base/utilities.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/base/timing.h>
#include <tissuefem/geometry/distribution.h>
#include <tissuefem/tool/grasp_tool.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace tissuefem::tool
{
  template <int dim>
  std::vector<unsigned int>
  vertices_within(const Triangulation<dim> &mesh,
                  const Point<dim>         &point,
                  const double              radius)
  {
    std::vector<unsigned int> vertices;
    const auto               &points = mesh.get_vertices();
    const auto               &used   = mesh.get_used_vertices();
    for (unsigned int v = 0; v < points.size(); ++v)
      if (used[v] && points[v].distance(point) <= radius)
        vertices.push_back(v);
    return vertices;
  }


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
    HapticParameters::declare_parameters(prm);
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
    enabled         = !Utilities::trim(grasp_point).empty();
    haptic.parse_parameters(prm, "Tool", enabled);
    prm.leave_subsection();
    if (!enabled)
      return;
    require(std::isfinite(radius) && radius > 0,
            "Tool/Grasp radius",
            "must be > 0 (length units) when 'Grasp point' is set");
    require(std::isfinite(grasp_time) && std::isfinite(release_time)
              && release_time > grasp_time,
            "Tool/Release time",
            "must be finite and later than 'Grasp time'");
  }


  template <int dim>
  GraspTool<dim>::GraspTool(const ToolParameters     &p,
                            const Triangulation<dim> &mesh)
      : parameters(p)
      , haptic(p.haptic, [this](const double t) { return displacement(t); })
  {
    const auto coordinates
      = parse_numbers(p.grasp_point, "Parameter 'Tool/Grasp point'");
    require(coordinates.size() == dim,
            "Tool/Grasp point",
            "needs " + std::to_string(dim) + " coordinates, got "
              + std::to_string(coordinates.size()));
    for (unsigned int d = 0; d < dim; ++d)
      grasp_point[d] = coordinates[d];
    vertices = vertices_within(mesh, grasp_point, p.radius);
    require(!vertices.empty(),
            "Tool/Grasp radius",
            "holds no vertex: none lies within " + std::to_string(p.radius)
              + " of 'Grasp point'");

    if (p.haptic.live_port >= 0)
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
    for (unsigned int d = 0; d < dim && p.haptic.live_port < 0; ++d)
      require(std::isfinite(displacement(p.grasp_time)[d]),
              "Tool/Trajectory",
              "is not finite at the grasp time");
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
  GraspTool<dim>::connect(const std::string &directory,
                          const double       body_diameter)
  {
    haptic.connect(directory, body_diameter);
  }


  template <int dim>
  Record<dim>
  GraspTool<dim>::record(const time::State &state,
                         solid::Solid<dim> &solid,
                         const contact::Reports<dim> &)
  {
    const auto values
      = solid.held_force(state.u, state.a, state.time, state.damping);
    Record<dim> result;
    for (unsigned int d = 0; d < dim; ++d)
      result.force[d] = values[d];
    result.position = displacement(state.time);
    result.engaged  = holding;
    result.haptic   = haptic.update(state.time, result.force, holding);
    last_force      = result.force;
    return result;
  }


  template <int dim>
  std::optional<Grasp<dim>>
  GraspTool<dim>::grasp(const double time) const
  {
    if (!holding)
      return std::nullopt;
    // u = u_grasp + d(t) - d(t_grasp) at the held vertices.
    return Grasp<dim>{grasp_point,
                      displacement(time) - displacement(grasp_time_actual),
                      last_force};
  }


  template <int dim>
  bool
  GraspTool<dim>::synchronize(const double time)
  {
    return haptic.synchronize(time, table);
  }


  template <int dim>
  std::string
  GraspTool<dim>::live_end() const
  {
    return haptic.live_end();
  }


  template <int dim>
  std::string
  GraspTool<dim>::summary() const
  {
    return "tool: " + std::to_string(vertices.size()) + " vertices held; "
           + haptic.summary();
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
    geometry::require_whole_mesh(mesh,
                                 "Tool/Grasp point",
                                 "a grasping tool holds vertices it finds "
                                 "in the whole mesh");
    return std::make_unique<GraspTool<dim>>(parameters, mesh);
  }

  template std::vector<unsigned int>
  vertices_within(const Triangulation<1> &, const Point<1> &, const double);
  template std::vector<unsigned int>
  vertices_within(const Triangulation<2> &, const Point<2> &, const double);
  template std::vector<unsigned int>
  vertices_within(const Triangulation<3> &, const Point<3> &, const double);

  template class GraspTool<1>;
  template class GraspTool<2>;
  template class GraspTool<3>;

  TISSUEFEM_REGISTER_TOOL(GraspTool,
                          "grasp",
                          "holds the vertices near 'Tool/Grasp point' from "
                          "'Grasp time' to 'Release time' and moves them along "
                          "a trajectory or a live device's positions.")
} // namespace tissuefem::tool
