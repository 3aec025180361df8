#pragma once

#include <deal.II/base/point.h>

#include <tissuefem/contact/penalty_contact.h>

#include <string>

namespace tissuefem::tool
{
  template <int dim>
  class ContactTool;
}

namespace tissuefem::output
{
  using namespace dealii;

  /**
   * The scene's rigid obstacles as the live view sends them (layouts in
   * doc/live_view.md): their names and roles in the page's greeting; their
   * drawings (contact::Shape::drawing(), in each shape's own frame) after
   * the surface's topology; and in every frame each one's pose, the force
   * the tissue exerts on it and, for the contact tool the mouse moves, the
   * mouse's offset. Process 0 only.
   */
  template <int dim>
  class ObstacleView
  {
  public:
    /// Floats per obstacle in a frame: translation (dim 3), rotation (3 x
    /// 3, row by row), force (3), touching (1), mouse offset (3).
    static constexpr unsigned int floats_per_obstacle = 19;

    /// @p contact: the scene's contact with obstacles (null: none);
    /// @p tool: the scene's contact tool (null: none).
    ObstacleView(const contact::PenaltyContact<dim> *contact,
                 const tool::ContactTool<dim>       *tool);

    /// A JSON array, one object per obstacle: "name", and "role": "tool"
    /// (the contact tool; "mouse" when the page's mouse moves it) or
    /// "obstacle".
    std::string
    json() const;

    /// Appends the number of obstacles (uint32), then for each the
    /// numbers of corners and triangles (uint32), the corners (float32, x y
    /// z; z = 0 in 2D) and the triangles (uint32, three corners each).
    /// Shapes without bounds are cut to a square of side @p extent about
    /// the point nearest @p centre.
    void
    append_drawings(std::string      &bytes,
                    const Point<dim> &centre,
                    const double      extent) const;

    /// Appends floats_per_obstacle float32 per obstacle at @p time, the
    /// forces from @p reports (the obstacles' forces on the tissue, of
    /// which these are the opposites).
    void
    append_poses(std::string                 &bytes,
                 const contact::Reports<dim> &reports,
                 const double                 time) const;

    /// The translation t' that places a drawing's corner y (in the shape's
    /// frame) where @p pose puts it: x = t' + R y (pose.h: x = c + t + R (y
    /// - c), so t' = c + t - R c).
    static Tensor<1, dim>
    placement(const contact::Pose<dim> &pose);

  private:
    const contact::PenaltyContact<dim> *contact;
    const tool::ContactTool<dim>       *tool;
  };
} // namespace tissuefem::output
