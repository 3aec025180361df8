#include <tissuefem/time/implicit_one_step.h>

namespace tissuefem::time
{
  /**
   * Backward Euler (problem session eqs 3-4): v_{n+1} = (u_{n+1} - u_n)/dt
   * and rho (v_{n+1} - v_n)/dt = div P + f at t_{n+1}. Dividing eq 4 by dt^2
   * gives c = 1/dt^2 and u_tilde = u_n + dt v_n; the acceleration is
   * a_{n+1} = (v_{n+1} - v_n)/dt = c (u_{n+1} - u_tilde). Unconditionally
   * stable and first-order accurate; it damps high frequencies.
   */
  class BackwardEuler : public ImplicitOneStep
  {
  public:
    explicit BackwardEuler(const ParameterHandler &)
    {
    }

    static void
    declare_parameters(ParameterHandler &)
    {
    }

  protected:
    double
    mass_coefficient(const double h) const override
    {
      return 1. / (h * h);
    }

    void
    predict(const State &old_state,
            const double h,
            VectorType  &u_tilde,
            VectorType  &initial_guess) const override
    {
      u_tilde = old_state.u;
      u_tilde.add(h, old_state.v);
      initial_guess = u_tilde;
    }

    void
    finish(const State      &old_state,
           const VectorType &u_tilde,
           const double      h,
           State            &new_state) const override
    {
      new_state.v = new_state.u;
      new_state.v -= old_state.u;
      new_state.v /= h;
      new_state.a = new_state.u;
      new_state.a -= u_tilde;
      new_state.a /= h * h;
    }
  };

  TISSUEFEM_REGISTER_INTEGRATOR(
    BackwardEuler,
    "backward Euler",
    "implicit first-order dynamics with consistent mass (Teran problem "
    "session eqs 3-6).")
} // namespace tissuefem::time
