#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <cmath>

namespace tissuefem::contact
{
  using namespace dealii;

  /**
   * Coulomb friction at one contact point, regularized by a tangential
   * penalty k and with the friction bound b = mu lambda held fixed over a
   * Newton solve (lambda the augmented Lagrangian's multiplier, updated
   * with it after each solve: Simo and Laursen 1992; Wriggers 2006,
   * chapter 5). The slip s = P (y - a) is the tangential part (P = I - n
   * (x) n) of the point's position y relative to its stick point a, both
   * in the obstacle's frame. Its potential
   *
   *   phi(s) = k |s|^2 / 2                  where k |s| <= b (stick),
   *   phi(s) = b |s| - b^2 / (2 k)          otherwise (slip),
   *
   * is convex and once differentiable, so that a step with friction stays
   * a minimization (the energy line search holds) with a symmetric
   * tangent. The force on the tissue is -dphi/ds: -k s sticking, -b s /
   * |s| sliding; the tangent d2phi/ds2 is k P, or b / |s| (P - t (x) t)
   * with t = s / |s|. The dependence of P on y through a curved obstacle's
   * normal is left out: exact on flat faces, a term of relative size |s|
   * times the curvature elsewhere.
   */
  template <int dim>
  struct Coulomb
  {
    /// The force on the tissue (stress units, per unit reference area).
    Tensor<1, dim> traction;
    /// phi (energy per unit reference area).
    double potential = 0;
    /// d2phi/dy2 (stress / length units).
    Tensor<2, dim> tangent;
    /// Whether the point slides (k |s| > b).
    bool slides = false;
    /// The unit slip direction t where it slides.
    Tensor<1, dim> direction;
    /// |s| (length units).
    double slip = 0;

    Coulomb(const Point<dim>     &y,
            const Point<dim>     &anchor,
            const Tensor<1, dim> &normal,
            const double          k,
            const double          bound)
    {
      const Tensor<2, dim> P
        = unit_symmetric_tensor<dim>() - outer_product(normal, normal);
      const Tensor<1, dim> s = P * (y - anchor);
      slip                   = s.norm();
      slides                 = k * slip > bound;
      if (!slides)
        {
          traction  = -k * s;
          potential = 0.5 * k * slip * slip;
          tangent   = k * P;
          return;
        }
      direction = s / slip;
      traction  = -bound * direction;
      potential = bound * slip - 0.5 * bound * bound / k;
      tangent   = bound / slip * (P - outer_product(direction, direction));
    }

    /// Where the stick point moves when the step is accepted: it stays
    /// while the point sticks and trails it by b / k along the slip while
    /// it slides.
    static Point<dim>
    new_anchor(const Point<dim>     &y,
               const Point<dim>     &anchor,
               const Tensor<1, dim> &normal,
               const double          k,
               const double          bound)
    {
      const Coulomb law(y, anchor, normal, k, bound);
      if (!law.slides)
        return anchor;
      return y - (bound / k) * law.direction;
    }
  };
} // namespace tissuefem::contact
