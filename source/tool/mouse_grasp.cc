#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_tools.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/geometry/distribution.h>
#include <tissuefem/tool/grasp_tool.h>
#include <tissuefem/tool/mouse_grasp.h>

#include <cmath>
#include <sstream>

namespace tissuefem::tool
{
  template <int dim>
  void
  MouseGrasp<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mouse");
    prm.declare_entry("Grasp radius",
                      "0",
                      Patterns::Double(0),
                      "With a live view ('Output/Live view/Port'), dragging "
                      "the surface with the mouse holds the vertices within "
                      "this distance of the picked point (length units; at "
                      "least the nearest vertex) and moves them with the "
                      "mouse. 0 (default): 3 % of the body's diameter.");
    prm.leave_subsection();
  }


  template <int dim>
  std::string
  MouseGrasp<dim>::unavailable(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.enter_subsection("Live view");
    const bool view = prm.get_integer("Port") >= 0;
    prm.leave_subsection();
    prm.leave_subsection();
    prm.enter_subsection("Tool");
    const bool grasping_tool = !Utilities::trim(prm.get("Grasp point")).empty();
    prm.leave_subsection();
    prm.enter_subsection("Mesh refinement");
    const bool adaptive = prm.get("Indicator") != "none";
    prm.leave_subsection();
    if (!view)
      return "no live view";
    if (dim < 2)
      return "a 1D body has no surface to pick";
    // The solid holds one set of vertices at a time.
    if (grasping_tool)
      return "the scene's own grasping tool holds the tissue";
    // Held vertices are those of the mesh at the grasp.
    if (adaptive)
      return "the mesh adapts";
    return {};
  }


  template <int dim>
  std::unique_ptr<Interface<dim>>
  MouseGrasp<dim>::create(ParameterHandler &prm, const Triangulation<dim> &mesh)
  {
    if (!unavailable(prm).empty())
      return nullptr;
    // Dragging picks the vertex nearest the mouse in the whole mesh.
    geometry::require_whole_mesh(mesh,
                                 "Output/Live view/Port",
                                 "dragging with the live view's mouse picks "
                                 "vertices of the whole mesh");
    prm.enter_subsection("Mouse");
    const double radius = prm.get_double("Grasp radius");
    prm.leave_subsection();
    return std::make_unique<MouseGrasp<dim>>(radius, mesh);
  }


  template <int dim>
  MouseGrasp<dim>::MouseGrasp(const double              radius,
                              const Triangulation<dim> &mesh)
      : radius(radius)
      , mesh(mesh)
  {
  }


  template <int dim>
  void
  MouseGrasp<dim>::connect(const std::string &, const double body_diameter)
  {
    diameter = body_diameter;
    motion.scale(diameter);
    if (radius == 0)
      radius = 0.03 * diameter;
    bounds = GridTools::compute_bounding_box(mesh);
    bounds.extend(0.1 * diameter);
  }


  template <int dim>
  std::string
  MouseGrasp<dim>::request_grasp(const Point<dim> &point)
  {
    for (unsigned int d = 0; d < dim; ++d)
      if (!std::isfinite(point[d]))
        return "grasp point outside the body";
    if (!bounds.point_inside(point))
      return "grasp point outside the body";
    asked_grasp = point;
    asked_drag  = Tensor<1, dim>();
    return {};
  }


  template <int dim>
  std::string
  MouseGrasp<dim>::request_drag(const Tensor<1, dim> &displacement)
  {
    if (std::string why = motion.refusal(displacement, "drag"); !why.empty())
      return why;
    asked_drag = displacement;
    return {};
  }


  template <int dim>
  void
  MouseGrasp<dim>::request_release()
  {
    asked_release = true;
  }


  template <int dim>
  bool
  MouseGrasp<dim>::synchronize(const double time)
  {
    // [grasp?, point, release?, drag] from process 0.
    std::vector<double> shared(2 + 2 * dim, 0.);
    if (parallel_tools::is_root())
      {
        shared[0] = asked_grasp ? 1 : 0;
        for (unsigned int d = 0; d < dim; ++d)
          {
            shared[1 + d]       = asked_grasp ? (*asked_grasp)[d] : 0;
            shared[2 + dim + d] = asked_drag[d];
          }
        shared[1 + dim] = asked_release ? 1 : 0;
        // A grasp asked while the tool still holds waits for the release.
        if (!held)
          asked_grasp.reset();
        asked_release = false;
      }
    shared = Utilities::MPI::broadcast(parallel_tools::communicator(), shared);
    if (shared[0] != 0 && !held)
      {
        for (unsigned int d = 0; d < dim; ++d)
          grasp_point[d] = shared[1 + d];
        vertices = vertices_within(mesh, grasp_point, radius);
        if (vertices.empty())
          vertices.push_back(GridTools::find_closest_vertex(mesh, grasp_point));
        grasp_due = true;
        motion.reset();
      }
    // A release stays due until act() lets go (a click may grasp and
    // release within one step).
    if (shared[1 + dim] != 0)
      release_due = held || grasp_due;
    for (unsigned int d = 0; d < dim; ++d)
      target[d] = shared[2 + dim + d];
    motion.advance(time, target);
    return true;
  }


  template <int dim>
  bool
  MouseGrasp<dim>::due(const double) const
  {
    return grasp_due || release_due;
  }


  template <int dim>
  void
  MouseGrasp<dim>::act(const time::State &state, solid::Solid<dim> &solid)
  {
    if (release_due && held)
      {
        solid.release();
        held        = false;
        release_due = false;
        target      = Tensor<1, dim>();
        motion.reset();
        return;
      }
    if (grasp_due)
      {
        solid.hold(
          vertices, [this](const double t) { return motion(t); }, state.u);
        held      = true;
        grasp_due = false;
        ++grasps;
      }
  }


  template <int dim>
  Record<dim>
  MouseGrasp<dim>::record(const time::State &state,
                          solid::Solid<dim> &solid,
                          const contact::Reports<dim> &)
  {
    Record<dim> result;
    if (held)
      {
        const auto values
          = solid.held_force(state.u, state.a, state.time, state.damping);
        for (unsigned int d = 0; d < dim; ++d)
          result.force[d] = values[d];
      }
    result.position = held ? motion(state.time) : Tensor<1, dim>();
    result.engaged  = held;
    last_force      = result.force;
    largest_force   = std::max(largest_force, result.force.norm());
    return result;
  }


  template <int dim>
  std::string
  MouseGrasp<dim>::summary() const
  {
    std::ostringstream s;
    s << "mouse: " << grasps << " grasp(s) from the live view, largest force "
      << largest_force << " (force units)";
    return s.str();
  }

  template class MouseGrasp<1>;
  template class MouseGrasp<2>;
  template class MouseGrasp<3>;

  TISSUEFEM_REGISTER_TOOL(MouseGrasp,
                          "mouse",
                          "the live view's mouse: dragging the surface holds "
                          "the vertices near the picked point and moves them "
                          "('Mouse/Grasp radius').")
} // namespace tissuefem::tool
