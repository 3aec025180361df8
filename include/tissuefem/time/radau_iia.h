#pragma once

#include <deal.II/base/parameter_handler.h>

#include <tissuefem/time/error_norm.h>
#include <tissuefem/time/first_order_system.h>
#include <tissuefem/time/interface.h>
#include <tissuefem/time/radau_linear_systems.h>
#include <tissuefem/time/stiffness.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace tissuefem::time
{
  using namespace dealii;

  /**
   * Jeffrey's implicit integrator (report section 3.3 and appendices D-E):
   * the 3-stage Radau IIA method, order 5, L-stable, with an adaptive step,
   * for the first-order form of eq 10 with the row-sum lumped mass m and
   * mass-proportional damping gamma = c m (eq D.18):
   *
   *   u' = v,   v' = (f_ext(t) - f_int(u)) / m - c v.
   *
   * Each call of advance() propagates over one 'Time step' (the report's
   * interval Delta t) with as many Runge-Kutta steps h as the error
   * estimate allows. The stage equations are solved by simplified Newton
   * in Hairer's transformed variables (D.16-D.17): one real system with
   * (gamma_hat/h) I - J and one complex with ((alpha_hat + i beta_hat)/h) I -
   * J. With J = [0 I; -K/m -c] each reduces to the displacements,
   * (K + s M) x = M (r_v + (sigma + c) r_u), s = sigma (sigma + c); the
   * complex one is solved as its real 2n x 2n form. 'Jacobian' selects K
   * (appendix E): analytical (the AD tangent), numerical (differenced
   * forces) or simplified (K = 0: diagonal, nothing assembled or
   * factorized). The Jacobian is re-evaluated at the start of a step only
   * when the previous Newton iteration contracted slowly (theta > 0.001),
   * and the matrices are refactorized when h changes by more than 20 %,
   * as RADAU5 does. Step size control, Newton stopping test and starting
   * values (the collocation polynomial of the last step, D.19 and
   * D.24-D.26 corrected) follow RADAU5; the embedded error estimate is
   * D.21-D.22.
   */
  class RadauIIA : public Interface
  {
  public:
    explicit RadauIIA(ParameterHandler &prm);

    static void
    declare_parameters(ParameterHandler &prm);

    void
    initialize(Context &c, State &state) override;

    StepReport
    advance(State &state, const double end_time) override;

    void
    mesh_changed() override;

    Capabilities
    capabilities() const override;

    std::string
    summary() const override;

  private:
    struct Attempt
    {
      bool         converged         = false;
      unsigned int newton_iterations = 0;
      double       error             = 0;
      double       next_step         = 0;
    };

    // Parameters.
    ErrorTolerances tolerances;
    std::string     jacobian_kind;
    bool            adaptive   = true;
    unsigned int    max_newton = 7;

    Context                   *context = nullptr;
    std::unique_ptr<Stiffness> stiffness;
    // Damping ratio, lumped mass and the mask of free entries.
    std::unique_ptr<FirstOrderSystem> system;

    // Stage increments Z, transformed W, derivatives F, the polynomial of
    // the last step (for starting values), and f at the step's start.
    std::array<VectorType, 3> zu, zv, wu, wv, fu, fv, pu, pv;
    VectorType                f0u, f0v;
    bool                      have_polynomial = false;
    double                    last_step       = 0;

    // Newton's two linear systems, built for the step factorized_step.
    std::unique_ptr<RadauLinearSystems> systems;
    double                              factorized_step  = 0;
    bool                                jacobian_current = false;

    double       h         = 0;
    double       faccon    = 1;
    double       theta     = 1;
    double       step_sum  = 0;
    unsigned int intervals = 0;
    StepReport   totals;
    bool         jacobian_fresh = false; // evaluated at the present state

    /// The lumped mass, the mask and the work vectors for the current
    /// mesh (laid out like @p like).
    void
    set_up_vectors(const VectorType &like);

    /// f(t, y) for y = (u, v): (v, (f_ext - f_int(u))/m - c v).
    void
    derivative(const double      t,
               const VectorType &u,
               const VectorType &v,
               VectorType       &du,
               VectorType       &dv);

    /// The tolerances' weighted RMS norm over the free entries.
    double
    scaled_norm(const std::vector<const VectorType *> &xu,
                const std::vector<const VectorType *> &xv,
                const State                           &y0,
                const VectorType                      *u1 = nullptr,
                const VectorType                      *v1 = nullptr) const
    {
      return tolerances.norm(xu, xv, system->free(), y0.u, y0.v, u1, v1);
    }


    /// One Runge-Kutta step of size @p step from @p state: the stages by
    /// simplified Newton, then the error estimate and the next step size.
    /// Leaves Z (zu, zv) for accept().
    Attempt
    try_step(const State &state, const double step);

    /// Starting values of the stage increments Z and their transformed
    /// form W for the step @p step (and the matrices for it).
    void
    start_stages(const State &state, const double step);

    /// Velocities of the prescribed entries that make the stage polynomial
    /// interpolate their prescribed displacements: V = A^-1 Z / h - v0.
    void
    set_boundary_velocities(const State &state, const double step);

    /// Simplified Newton on the stage equations. Returns whether it
    /// converged; if not, @p attempt says which step to try next.
    bool
    solve_stages(const State &state, const double step, Attempt &attempt);

    /// F_i = f(t0 + c_i h, y0 + Z_i) for the three stages; false if the
    /// state of a stage cannot be evaluated (an inverted element).
    bool
    evaluate_stages(const State &state, const double step);

    /// Newton's increments of W: the transformed residuals T^-1 F - Lambda
    /// W / h on the free entries, solved with the two linear systems.
    void
    newton_increments(const State               &state,
                      const double               step,
                      std::array<VectorType, 3> &ru,
                      std::array<VectorType, 3> &rv);

    /// The embedded error estimate of the converged stages and the step
    /// size RADAU5's controller takes from it, into @p attempt.
    void
    estimate_error(const State &state, const double step, Attempt &attempt);

    void
    accept(State &state, const double step, StepReport &report);
  };
} // namespace tissuefem::time
