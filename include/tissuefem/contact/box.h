#pragma once

#include <tissuefem/contact/shape.h>

namespace tissuefem::contact
{
  /**
   * A box (a retractor's blade, a tray, a bone block), axis-aligned or
   * turned by a rotation: in its own axes q = R^T (y - c) it is |q_i| <=
   * h_i. Outside, the gap is the distance |w| to the box, w the excess of
   * |q| over h in the components where it is positive, and n = R sign(q)
   * w / |w|: near a face n is that face's normal (no curvature), near an
   * edge or a corner the box is rounded by its distance field, with the
   * gradient R (P - n' (x) n') R^T / |w|, P projecting on the exceeded
   * axes. Inside, the gap is the (negative) distance to the nearest face,
   * whose normal n is, without curvature.
   */
  template <int dim>
  class Box : public Shape<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    explicit Box(ParameterHandler &prm);

    Gap<dim>
    gap(const Point<dim> &y) const override;

    Drawing<dim>
    drawing(const Point<dim> &centre, const double extent) const override;

  private:
    Point<dim>     centre;
    Tensor<1, dim> half;
    /// Columns: the box's axes in the scene's frame.
    Tensor<2, dim> rotation;
  };
} // namespace tissuefem::contact
