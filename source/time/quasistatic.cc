#include <tissuefem/time/interface.h>

namespace tissuefem::time
{
  /**
   * Quasistatics (lecture notes eq 2.11): inertia is neglected, each step
   * solves f_int(u) = f_ext(t_{n+1}) with the boundary data at t_{n+1},
   * starting from the previous equilibrium. The reported velocity is the
   * difference quotient (u_{n+1} - u_n)/dt.
   */
  class Quasistatic : public Interface
  {
  public:
    explicit Quasistatic(const ParameterHandler &)
    {
    }

    static void
    declare_parameters(ParameterHandler &)
    {
    }

    double
    mass_coefficient(const double) const override
    {
      return 0.;
    }

    void
    predict(const Vector<double> &u_old,
            const Vector<double> &,
            const double,
            Vector<double> &u_tilde,
            Vector<double> &initial_guess) const override
    {
      u_tilde       = u_old;
      initial_guess = u_old;
    }
  };

  TISSUEFEM_REGISTER_INTEGRATOR(
    Quasistatic,
    "quasistatic",
    "equilibrium at every load step, inertia neglected (lecture notes "
    "section 2.4).")
} // namespace tissuefem::time
