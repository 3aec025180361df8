#include <tissuefem/time/interface.h>

namespace tissuefem::time
{
  /**
   * Backward Euler (problem session eqs 3-4): v_{n+1} = (u_{n+1} - u_n)/dt
   * and rho (v_{n+1} - v_n)/dt = div P + f at t_{n+1}. Dividing eq 4 by dt^2
   * gives c = 1/dt^2 and u_tilde = u_n + dt v_n. Unconditionally stable and
   * first-order accurate; it damps high frequencies.
   */
  class BackwardEuler : public Interface
  {
  public:
    explicit BackwardEuler(const ParameterHandler &)
    {
    }

    static void
    declare_parameters(ParameterHandler &)
    {
    }

    double
    mass_coefficient(const double dt) const override
    {
      return 1. / (dt * dt);
    }

    void
    predict(const Vector<double> &u_old,
            const Vector<double> &v_old,
            const double          dt,
            Vector<double>       &u_tilde,
            Vector<double>       &initial_guess) const override
    {
      u_tilde = u_old;
      u_tilde.add(dt, v_old);
      initial_guess = u_tilde;
    }
  };

  TISSUEFEM_REGISTER_INTEGRATOR(
    BackwardEuler,
    "backward Euler",
    "implicit first-order dynamics with consistent mass (Teran problem "
    "session eqs 3-6).")
} // namespace tissuefem::time
