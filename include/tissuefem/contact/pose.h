#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <tissuefem/contact/shape.h>

#include <array>

namespace tissuefem::contact
{
  using namespace dealii;

  /// The number of rotation parameters in @p dim dimensions: none on a
  /// line, an angle in the plane, a rotation vector in space.
  constexpr unsigned int
  rotation_components(const int dim)
  {
    return dim == 2 ? 1 : dim == 3 ? 3 : 0;
  }

  /**
   * The rotation given by @p angles (radians): in 2D the angle
   * counter-clockwise, angles[0]; in 3D the rotation vector (the axis times
   * the angle, right-handed), by Rodrigues' formula; the identity in 1D.
   */
  template <int dim>
  Tensor<2, dim>
  rotation_matrix(const std::array<double, 3> &angles);

  /**
   * Where a rigid obstacle's shape is at one time: the shape's own frame
   * (shape.h) rotated by R about the pivot c (a point of that frame, the
   * obstacle's 'Rotation centre') and then translated by t, so that the
   * shape's point y lies at
   *
   *   x = c + t + R (y - c).
   *
   * Gaps are computed in the shape's frame and turned back: the distance
   * is unchanged, the normal is R n and its gradient R (dn/dy) R^T (dy/dx
   * = R^T).
   */
  template <int dim>
  struct Pose
  {
    Tensor<1, dim> translation;
    Tensor<2, dim> rotation = unit_symmetric_tensor<dim>();
    Point<dim>     pivot;
    /// Whether rotation differs from the identity (the translation alone
    /// is then applied, without products).
    bool rotates = false;

    /// The shape's frame's point at the world's point @p x.
    Point<dim>
    local(const Point<dim> &x) const
    {
      if (!rotates)
        return x - translation;
      return pivot + transpose(rotation) * (x - translation - pivot);
    }

    /// The world's point at the shape's frame's point @p y.
    Point<dim>
    world(const Point<dim> &y) const
    {
      if (!rotates)
        return y + translation;
      return pivot + translation + rotation * (y - pivot);
    }

    /// A vector of the shape's frame in the world.
    Tensor<1, dim>
    world_vector(const Tensor<1, dim> &v) const
    {
      return rotates ? rotation * v : v;
    }

    /// A vector of the world in the shape's frame.
    Tensor<1, dim>
    local_vector(const Tensor<1, dim> &v) const
    {
      return rotates ? transpose(rotation) * v : v;
    }

    /// The gap @p g computed in the shape's frame, in the world.
    Gap<dim>
    world_gap(Gap<dim> g) const
    {
      if (rotates)
        {
          g.normal = rotation * g.normal;
          g.normal_gradient
            = rotation * g.normal_gradient * transpose(rotation);
        }
      return g;
    }
  };
} // namespace tissuefem::contact
