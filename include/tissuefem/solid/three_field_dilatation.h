#pragma once

#include <deal.II/lac/vector.h>

#include <vector>

namespace tissuefem::solid
{
  using namespace dealii;

  /**
   * The three-field form of the mean dilatation (F-bar) element: the cell
   * dilatation theta~ and pressure p as Newton unknowns of their own, as
   * in the Hu-Washizu element of Simo, Taylor and Pister (1985) and
   * deal.II's step-44, instead of theta = theta(u) and p = Phi_theta / V
   * recomputed from u at every iterate (mean_dilatation.h).
   *
   * Why: in the condensed element a nearly incompressible material turns
   * the second-order error of a Newton step in theta(u) into a pressure
   * error of bulk modulus times it (4e5 on Cook's membrane at nu =
   * 0.4999), and those pressures wreck the next tangent: Newton needs 8-13
   * damped iterations per load step and fails on whole-load steps and
   * after mesh changes. Here theta~ and p move linearly with the update
   * and the constraint theta(u) = theta~ is met at convergence, so the
   * iterates stay near the equilibrium path. The converged answer is the
   * same discrete solution: the condensed element's.
   *
   * Per cell, with W(u, theta~) = sum_q w_q phi(F_q, theta~), phi(F,
   * theta) = Psi((theta / det F)^(1/d) F), V the cell volume and b =
   * dtheta/du, the equations are
   *
   *   R_u     = dW/du + p V b                  = 0   (momentum),
   *   R_theta = Phi_theta - p V                = 0   (Phi_theta = dW/dtheta~),
   *   r       = theta(u) - theta~              = 0   (the constraint).
   *
   * Their Newton step, with C = d2W/du dtheta~ and Theta = d2W/dtheta~2:
   *
   *   dtheta = b.du + r,   dp = (R_theta + C.du + Theta dtheta) / V,
   *
   * and, substituted into the momentum rows, the condensed element's own
   * tangent K + C b^T + b C^T + Theta b b^T (with p in place of
   * Phi_theta / V) on the right-hand side
   *
   *   -(R_u + C r + b (R_theta + Theta r)).
   *
   * At a consistent state (r = 0, R_theta = 0) this is the condensed
   * element's Newton step exactly. This class keeps the per-cell unknowns
   * and linearization; the Solid assembles the cells (three_field_cell).
   * Cells are the locally owned ones, indexed as the Solid's CellCache.
   */
  class ThreeFieldDilatation
  {
  public:
    /// Starts a step on @p n_cells cells: the next assembly initializes
    /// every cell (initializing()).
    void
    begin(const unsigned int n_cells);

    /// Whether the cells' unknowns are still to be set from u (by the
    /// first assembly after begin(), which then calls initialized()).
    bool
    initializing() const
    {
      return initialize;
    }
    void
    initialized()
    {
      initialize = false;
    }

    bool
    active() const
    {
      return is_active;
    }

    void
    end()
    {
      is_active  = false;
      initialize = false;
    }

    /// The cell's dilatation theta~ and pressure p (stress units).
    double &
    theta(const unsigned int c)
    {
      return cells[c].theta;
    }
    double &
    pressure(const unsigned int c)
    {
      return cells[c].p;
    }

    /// Whether cell @p c has a linearization (a Jacobian was assembled
    /// there since begin()).
    bool
    linearized(const unsigned int c) const
    {
      return !cells[c].b.empty();
    }

    /// Stores the cell's linearization: b = dtheta/du and C = d2W/du
    /// dtheta~ by the cell's local dofs, Theta and the volume V.
    void
    set_linearization(const unsigned int    c,
                      std::vector<double> &&b,
                      std::vector<double> &&C,
                      const double          Theta,
                      const double          volume);

    /// Records the cell's constraint and pressure residuals r and R_theta
    /// and adds the condensed rows C r + b (R_theta + Theta r) to the
    /// cell's momentum residual @p rhs (local dofs).
    void
    add_condensed_rows(const unsigned int c,
                       const double       r,
                       const double       R_theta,
                       Vector<double>    &rhs);

    /// The increments of cell @p c for its local displacement update
    /// @p du; trial(alpha) then moves along them.
    void
    predict(const unsigned int c, const std::vector<double> &du);

    /// theta~ and p at step length @p alpha along the last prediction.
    void
    trial(const double alpha);

  private:
    struct Cell
    {
      double theta = 0, p = 0;
      /// Where the last prediction started, and its increments.
      double base_theta = 0, base_p = 0, d_theta = 0, d_p = 0;
      /// Residuals at the last assembly.
      double r = 0, R_theta = 0;
      /// Linearization at the last Jacobian.
      std::vector<double> b, C;
      double              Theta = 0, volume = 0;
    };
    std::vector<Cell> cells;
    bool              is_active = false, initialize = false;
  };
} // namespace tissuefem::solid
