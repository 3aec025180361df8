#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <cmath>

namespace tissuefem::contact
{
  using namespace dealii;

  /**
   * Coulomb friction at one contact point by the augmented Lagrangian
   * (Simo and Laursen 1992; Wriggers 2006, chapter 5): the tangential
   * traction is
   *
   *   t = proj_b(z),  z = P tau - k s,
   *
   * with tau the point's tangential multiplier (a traction, updated to t
   * after each converged solve, as the normal multiplier is), s = P (y -
   * a) the slip of the point's position y from its stick point a (all in
   * the world's frame: PenaltyContact keeps y - a and tau in the
   * obstacle's and turns them; P = I - n (x) n), k the penalty, and proj_b the
   * projection onto the disc |t| <= b of the friction bound b = mu lambda,
   * held fixed over a solve. Where the updates settle (t = tau), either
   * s = 0 and |t| <= b (stick, exactly, whatever k), or |t| = b with t
   * against the slip (slide): Coulomb's law with maximal dissipation.
   *
   * Over a solve, t = -dphi/dy with the convex, once differentiable
   *
   *   phi = |z|^2 / (2 k)                  where |z| <= b (stick),
   *   phi = (b |z| - b^2 / 2) / k          otherwise (slide),
   *
   * so that a step with friction stays a minimization (the energy line
   * search holds) with a symmetric tangent d2phi/dy2: k P sticking,
   * k b / |z| (P - d (x) d) sliding, d = z / |z|. The dependence of P on y
   * through a curved obstacle's normal is left out: exact on flat faces,
   * a term of relative size |s| times the curvature elsewhere.
   */
  template <int dim>
  struct Coulomb
  {
    /// The tangential force on the tissue t (stress units, per unit
    /// reference area).
    Tensor<1, dim> traction;
    /// phi (energy per unit reference area).
    double potential = 0;
    /// d2phi/dy2 (stress / length units).
    Tensor<2, dim> tangent;
    /// Whether the point slides (|z| > b).
    bool slides = false;

    Coulomb(const Point<dim>     &y,
            const Point<dim>     &anchor,
            const Tensor<1, dim> &normal,
            const double          k,
            const double          bound,
            const Tensor<1, dim> &tau)
    {
      const Tensor<2, dim> P
        = unit_symmetric_tensor<dim>() - outer_product(normal, normal);
      const Tensor<1, dim> z    = P * tau - k * (P * (y - anchor));
      const double         size = z.norm();
      slides                    = size > bound;
      if (!slides)
        {
          traction  = z;
          potential = 0.5 * size * size / k;
          tangent   = k * P;
          return;
        }
      const Tensor<1, dim> d = z / size;
      traction               = bound * d;
      potential              = (bound * size - 0.5 * bound * bound) / k;
      tangent                = k * bound / size * (P - outer_product(d, d));
    }
  };
} // namespace tissuefem::contact
