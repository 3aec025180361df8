#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <utility>
#include <vector>

namespace tissuefem::contact
{
  using namespace dealii;

  /**
   * Triangles that draw a rigid shape (Shape::drawing(), for the live
   * view), in the shape's own frame: in 3D its surface, each triangle
   * counter-clockwise seen from outside; in 2D the region it covers,
   * counter-clockwise seen from +z. Empty in 1D, where nothing is drawn.
   */
  template <int dim>
  struct Drawing
  {
    std::vector<Point<dim>> vertices;
    /// Three vertex indices per triangle.
    std::vector<unsigned int> triangles;
  };

  namespace drawing
  {
    /// How finely curved shapes are drawn: segments around a circle.
    constexpr unsigned int segments = 32;

    /**
     * The closed surface (3D) or region (2D) swept by the profile @p
     * profile, pairs (s, r) of a position s along the unit axis @p axis
     * from @p origin and a distance r >= 0 from it, from one pole (r = 0)
     * to the other (r = 0): in 3D turned about the axis, in 2D mirrored
     * across it (a convex profile gives a convex polygon).
     */
    template <int dim>
    Drawing<dim>
    revolve(const std::vector<std::pair<double, double>> &profile,
            const Point<dim>                             &origin,
            const Tensor<1, dim>                         &axis);

    /// Two unit vectors a, b that make (a, b, @p axis) a right-handed
    /// orthonormal frame (@p axis a unit vector).
    std::pair<Tensor<1, 3>, Tensor<1, 3>>
    tangent_frame(const Tensor<1, 3> &axis);

    /// The profile of a capsule of radius @p radius about the segment
    /// [0, length] of its axis (a ball for length 0): a half circle, the
    /// shaft, a half circle.
    std::vector<std::pair<double, double>>
    capsule_profile(const double length, const double radius);

    /// The volume (3D) or area (2D) a drawing encloses, by the divergence
    /// theorem (3D) or the shoelace formula (2D): positive when its
    /// triangles are turned as Drawing says.
    template <int dim>
    double
    enclosed_measure(const Drawing<dim> &d);

    /// Turns every triangle of a closed drawing around if it encloses a
    /// negative measure.
    template <int dim>
    void
    orient_outwards(Drawing<dim> &d);
  } // namespace drawing
} // namespace tissuefem::contact
