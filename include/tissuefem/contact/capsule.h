#pragma once

#include <tissuefem/contact/shape.h>

namespace tissuefem::contact
{
  /**
   * An instrument's shaft with a rounded tip: all points within a radius
   * R of the segment from a to b (a stadium in 2D). The gap of y is |y -
   * c| - R, c the segment's point nearest y, and n = (y - c) / |y - c|. Its
   * gradient is that of a sphere about an end, (I - n (x) n) / |y - c|,
   * and that of a cylinder along the shaft, (I - n (x) n - e (x) e) / |y -
   * c| with e the axis: the shaft curves only around its axis.
   */
  template <int dim>
  class Capsule : public Shape<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    explicit Capsule(ParameterHandler &prm);

    Gap<dim>
    gap(const Point<dim> &y) const override;

    double
    distance(const Point<dim> &y) const override;

    Drawing<dim>
    drawing(const Point<dim> &centre, const double extent) const override;

  private:
    Point<dim>     start;
    Tensor<1, dim> axis;
    double         length;
    double         radius;
  };
} // namespace tissuefem::contact
