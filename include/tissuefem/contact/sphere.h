#pragma once

#include <tissuefem/contact/shape.h>

namespace tissuefem::contact
{
  /**
   * A ball of radius R about a centre c (a probe's tip; in 2D a disc):
   * the gap of y is |y - c| - R, the normal n = (y - c) / |y - c| and its
   * gradient (I - n (x) n) / |y - c|, the curvature that makes Newton's
   * tangent consistent where the tissue slides around the ball.
   */
  template <int dim>
  class Sphere : public Shape<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    explicit Sphere(ParameterHandler &prm);

    Gap<dim>
    gap(const Point<dim> &y) const override;

    double
    distance(const Point<dim> &y) const override;

    Drawing<dim>
    drawing(const Point<dim> &centre, const double extent) const override;

  private:
    Point<dim> centre;
    double     radius;
  };
} // namespace tissuefem::contact
