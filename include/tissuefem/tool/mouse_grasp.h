#pragma once

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <tissuefem/tool/interface.h>
#include <tissuefem/tool/mouse_motion.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace tissuefem::tool
{
  using namespace dealii;

  /**
   * The live view's mouse as a grasping tool: a page picks a point of the
   * surface and drags it; the vertices within 'Mouse/Grasp radius' of the
   * picked point (reference coordinates; at least the nearest vertex) are
   * held and follow the drag, u = u_grasp + D(t), until the page lets go.
   * It exists in runs with a live view ('Output/Live view/Port' >= 0, dim
   * 2 or 3) whose scene has no grasping tool of its own (the solid holds
   * one set of vertices at a time) and no adaptive mesh (held vertices are
   * those of one mesh): unavailable() says which. Checkpoints are written
   * while it holds nothing (checkpointable()): a restarted run has nothing
   * grasped, as when the page leaves.
   *
   * The page's requests arrive on process 0 (request_grasp(), request_drag(),
   * request_release(), from the live view), at any time; synchronize(),
   * before each step and on every process, shares them. What a page may ask
   * is bounded as for a device on the live port: a grasp point within the
   * body's bounding box (grown by a tenth of its diameter), a drag of at
   * most the body's diameter; the tool moves towards the dragged position
   * by at most a tenth of the diameter per step, linearly over the step, so
   * a fast mouse neither tears the mesh nor stalls the solver.
   */
  template <int dim>
  class MouseGrasp : public Interface<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    /// Why a run with the parameters @p prm has no mouse tool (empty: it
    /// has one).
    static std::string
    unavailable(ParameterHandler &prm);

    /// The tool, unless unavailable(); else null.
    static std::unique_ptr<Interface<dim>>
    create(ParameterHandler &prm, const Triangulation<dim> &mesh);

    MouseGrasp(const double radius, const Triangulation<dim> &mesh);

    /// Process 0: a page grasps at @p point (reference coordinates).
    /// Returns why not (empty: taken, from the next step on).
    std::string
    request_grasp(const Point<dim> &point);
    /// Process 0: the grasped point's displacement since the grasp.
    std::string
    request_drag(const Tensor<1, dim> &displacement);
    /// Process 0: lets go at the next step.
    void
    request_release();

    /// Shares process 0's requests; sets the motion over the step to
    /// @p time.
    bool
    synchronize(const double time) override;
    bool
    due(const double time) const override;
    void
    act(const time::State &state, solid::Solid<dim> &solid) override;
    void
    connect(const std::string &directory, const double body_diameter) override;
    /// Not while it holds vertices (a checkpoint keeps no hold); else a
    /// restart has nothing grasped, as when the page leaves.
    bool
    checkpointable() const override
    {
      return !held;
    }
    Record<dim>
    record(const time::State           &state,
           solid::Solid<dim>           &solid,
           const contact::Reports<dim> &contact) override;
    std::string
    summary() const override;

    std::optional<Grasp<dim>>
    grasp(const double time) const override
    {
      if (!held)
        return std::nullopt;
      return Grasp<dim>{grasp_point, motion(time), last_force};
    }

  private:
    double                    radius;
    const Triangulation<dim> &mesh;
    /// Where a page may grasp: the body's box grown by a tenth of its
    /// diameter (set by connect()).
    BoundingBox<dim> bounds;
    double           diameter = 1;

    // Process 0: what the pages asked since the last synchronize().
    std::optional<Point<dim>> asked_grasp;
    Tensor<1, dim>            asked_drag;
    bool                      asked_release = false;

    // Shared by synchronize().
    bool                      grasp_due = false, release_due = false;
    bool                      held = false;
    Point<dim>                grasp_point;
    std::vector<unsigned int> vertices;
    /// The held vertices' motion, and where the page asks it to go.
    MouseMotion<dim> motion;
    Tensor<1, dim>   target;
    Tensor<1, dim>   last_force;
    unsigned int     grasps        = 0;
    double           largest_force = 0;
  };
} // namespace tissuefem::tool
