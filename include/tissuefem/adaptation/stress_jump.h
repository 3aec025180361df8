#pragma once

#include <deal.II/lac/vector.h>

#include <tissuefem/solid/solid.h>

namespace tissuefem::adaptation
{
  /**
   * The residual (Babuska-Rheinboldt) error estimator of the balance of
   * momentum, restricted to its face terms: per cell K,
   *   eta_K^2 = sum over faces F of K of  c_F h_K int_F |R_F|^2 dS / (2 mu)^2
   * with R_F the jump [P N] of the first Piola-Kirchhoff traction across an
   * interior face (c_F = 1/2: each side carries half) and P N - t on a
   * boundary face with prescribed traction t (zero on free boundaries; the
   * components a Dirichlet condition prescribes are left out; c_F = 1).
   * Where Kelly's indicator measures jumps of Grad u, this measures the
   * force imbalance itself, so it weighs regions by their stiffness and
   * load, and the total estimate (sum eta_K^2)^(1/2) is one for the H1
   * seminorm error (in its units, through mu = A_0101 at F = I), whose
   * effectivity a manufactured solution measures. The volume residual
   * Div P + b is left out: for low-order elements the face jumps dominate
   * (Verfuerth, A Posteriori Error Estimation Techniques, 2013, sec. 4.3).
   * Faces between a cell and a coarser neighbour are seen from the finer
   * side only. The plain F is used, also under the mean-dilatation
   * formulation.
   */
  template <int dim>
  void
  stress_jump_indicator(const solid::Solid<dim> &solid,
                        const VectorType        &u_ghosted,
                        const double             time,
                        Vector<float>           &indicator);

  /// (sum over all cells of eta_K^2)^(1/2) (collective over processes).
  template <int dim>
  double
  stress_jump_estimate(const solid::Solid<dim> &solid,
                       const VectorType        &u_ghosted,
                       const double             time);
} // namespace tissuefem::adaptation
