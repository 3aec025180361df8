#pragma once

#include <tissuefem/contact/shape.h>

namespace tissuefem::contact
{
  /**
   * The half-space behind a plane: a table, a bed, a floor. The plane
   * passes through 'Point' with unit outward normal 'Normal' (normalized
   * here); the gap of y is (y - point) . normal, the normal is constant
   * and its gradient zero.
   */
  template <int dim>
  class HalfSpace : public Shape<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    explicit HalfSpace(ParameterHandler &prm);

    Gap<dim>
    gap(const Point<dim> &y) const override;

    Drawing<dim>
    drawing(const Point<dim> &centre, const double extent) const override;

  private:
    Point<dim>     point;
    Tensor<1, dim> normal;
  };
} // namespace tissuefem::contact
