#pragma once

#include <deal.II/base/tensor.h>

#include <vector>

namespace tissuefem::solid
{
  using namespace dealii;

  /**
   * The F-bar (mean dilatation) element: the three-field Hu-Washizu
   * element of Simo, Taylor and Pister (1985) with the dilatation theta
   * and the pressure constant per cell, condensed. The energy of a cell is
   *
   *   W = sum_q w_q Psi(Fbar_q),  Fbar_q = (theta / J_q)^(1/d) F_q,
   *   theta = sum_q w_q J_q / V,  V = sum_q w_q,
   *
   * so the volume change seen by the material is the cell mean one and a
   * nearly incompressible material constrains one volume per cell instead
   * of one per quadrature point: no volumetric locking on Q1 (Q1-P0), Q2
   * (Q2-P0) and P2 (P2-P0). Any energy works, since Psi is only evaluated.
   *
   * Writing phi(F, theta) = Psi((theta/det F)^(1/d) F), the cell residual
   * and tangent follow by the chain rule through theta(u):
   *
   *   dW/du = sum_q w_q (phi_F + Phi_theta/V cof F_q) : dF_q/du,
   *   Phi_theta = sum_q w_q phi_theta,
   *
   * and the tangent adds to the per-point A_q = phi_FF + Phi_theta/V
   * dcof/dF the cell-wide rank-two term C b^T + b C^T + Theta b b^T, with
   * b = dtheta/du, C = sum_q w_q phi_Ftheta : dF_q/du and Theta = sum_q
   * w_q phi_thetatheta.
   */
  template <int dim>
  struct MeanDilatationPoint
  {
    Tensor<2, dim> phi_F;
    double         phi_theta = 0;
    Tensor<4, dim> phi_FF;
    Tensor<2, dim> phi_F_theta;
    double         phi_theta_theta = 0;
  };

  /// theta = sum w_q J_q / sum w_q; returns a value <= 0 (the smallest J)
  /// if some J_q <= 0, where Fbar is not defined.
  template <int dim>
  double
  mean_dilatation(const std::vector<Tensor<2, dim>> &F,
                  const double                      *JxW,
                  const unsigned int                 n_q);

  /// Fbar = (theta / det F)^(1/d) F.
  template <int dim>
  Tensor<2, dim>
  modified_deformation_gradient(const Tensor<2, dim> &F, const double theta);

  /**
   * Replaces the deformation gradients of one cell's @p n_q points by their
   * Fbar for the dilatation @p theta; returns false (leaving them) where
   * Fbar is not defined (theta / det F <= 0 at some point).
   */
  template <int dim>
  bool
  apply_dilatation(std::vector<Tensor<2, dim>> &F,
                   const unsigned int           n_q,
                   const double                 theta);

  /**
   * Replaces the deformation gradients of one cell by their Fbar for its
   * mean dilatation times @p carried (a dilatation carried across a mesh
   * change, DilatationCarry; 1 otherwise); returns false (leaving them) if
   * some det F <= 0.
   */
  template <int dim>
  bool
  apply_mean_dilatation(std::vector<Tensor<2, dim>> &F,
                        const double                *JxW,
                        const unsigned int           n_q,
                        const double                 carried = 1);

  /// phi_F and phi_theta in closed form from Pbar = dPsi/dF at Fbar:
  /// phi_F = s Pbar - (Pbar : Fbar)/d F^-T, phi_theta = (Pbar : Fbar)/(d
  /// theta), s = (theta/J)^(1/d).
  template <int dim>
  void
  mean_dilatation_stress(const Tensor<2, dim>     &F,
                         const double              theta,
                         const Tensor<2, dim>     &P_bar,
                         MeanDilatationPoint<dim> &point);

  /// All first and second derivatives of phi(F, theta) from Pbar and Abar
  /// = d2Psi/dF2 at Fbar, chained with the derivatives of the map (F,
  /// theta) -> Fbar = s F, s = (theta / J)^(1/d), in closed form: ds/dF =
  /// -(s/d) F^{-T}, ds/dtheta = s / (d theta), and their derivatives.
  template <int dim>
  void
  mean_dilatation_stress_and_tangent(const Tensor<2, dim>     &F,
                                     const double              theta,
                                     const Tensor<2, dim>     &P_bar,
                                     const Tensor<4, dim>     &A_bar,
                                     MeanDilatationPoint<dim> &point);

  /// The same by nested forward AD numbers through the map (F, theta) ->
  /// Fbar: an independent derivation, which the tests compare with
  /// (unit/element_consistency).
  template <int dim>
  void
  mean_dilatation_stress_and_tangent_by_ad(const Tensor<2, dim>     &F,
                                           const double              theta,
                                           const Tensor<2, dim>     &P_bar,
                                           const Tensor<4, dim>     &A_bar,
                                           MeanDilatationPoint<dim> &point);
} // namespace tissuefem::solid
