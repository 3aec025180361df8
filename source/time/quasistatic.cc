#include <tissuefem/time/implicit_one_step.h>

namespace tissuefem::time
{
  /**
   * Quasistatics (lecture notes eq 2.11): inertia is neglected, each step
   * solves f_int(u) = f_ext(t_{n+1}) with the boundary data at t_{n+1},
   * starting from the previous equilibrium. The reported velocity is the
   * difference quotient (u_{n+1} - u_n)/dt; the acceleration is zero.
   */
  class Quasistatic : public ImplicitOneStep
  {
  public:
    explicit Quasistatic(const ParameterHandler &)
    {
    }

    static void
    declare_parameters(ParameterHandler &)
    {
    }

  protected:
    double
    mass_coefficient(const double) const override
    {
      return 0.;
    }

    void
    predict(const State &old_state,
            const double h,
            VectorType  &u_tilde,
            VectorType  &initial_guess) const override
    {
      u_tilde       = old_state.u;
      initial_guess = old_state.u;
      // v is the last step's difference quotient: linear extrapolation.
      if (context->time.extrapolate)
        initial_guess.add(h, old_state.v);
    }

    void
    finish(const State &old_state,
           const VectorType &,
           const double h,
           State       &new_state) const override
    {
      new_state.v = new_state.u;
      new_state.v -= old_state.u;
      new_state.v /= h;
      new_state.a.reinit(new_state.u);
    }
  };

  TISSUEFEM_REGISTER_INTEGRATOR(
    Quasistatic,
    "quasistatic",
    "equilibrium at every load step, inertia neglected (lecture notes "
    "section 2.4).")
} // namespace tissuefem::time
