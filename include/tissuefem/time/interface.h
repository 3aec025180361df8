#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/base/registry.h>

namespace tissuefem::time
{
  using namespace dealii;

  /**
   * A one-step time integrator for M a + f_int(u) = f_ext, written so that
   * each step is the nonlinear system
   *
   *   c M (u - u_tilde) + f_int(u) - f_ext(t_{n+1}) = 0
   *
   * for u = u_{n+1}: the integrator supplies c, u_tilde and the initial
   * guess, and the new velocity once u is known.
   */
  class Interface
  {
  public:
    virtual ~Interface() = default;

    /// The coefficient c of the mass term for step size @p dt.
    virtual double
    mass_coefficient(const double dt) const = 0;

    /// Fills u_tilde and the Newton initial guess from (u_n, v_n).
    virtual void
    predict(const Vector<double> &u_old,
            const Vector<double> &v_old,
            const double          dt,
            Vector<double>       &u_tilde,
            Vector<double>       &initial_guess) const = 0;

    /// v_{n+1} from u_{n+1}, u_n and v_n. The default is the difference
    /// quotient (u_{n+1} - u_n)/dt, which backward Euler uses (eq 3a) and
    /// quasistatics reports.
    virtual void
    velocity(const Vector<double> &u_new,
             const Vector<double> &u_old,
             const Vector<double> & /*v_old*/,
             const double    dt,
             Vector<double> &v_new) const
    {
      v_new = u_new;
      v_new -= u_old;
      v_new /= dt;
    }
  };

  using IntegratorRegistry = Registry<Interface, const ParameterHandler &>;

  /// The 'Time integration' subsection.
  struct TimeParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    std::string  integrator;
    double       end_time;
    double       time_step;
    unsigned int max_step_halvings;
  };
} // namespace tissuefem::time

/// Registers a time integrator at the end of its source file. @p Class must
/// be constructible from a ParameterHandler and have a static
/// declare_parameters(ParameterHandler &).
#define TISSUEFEM_REGISTER_INTEGRATOR(Class, name, description) \
  namespace                                                     \
  {                                                             \
    const bool tissuefem_registered_##Class = [] {              \
      ::tissuefem::time::IntegratorRegistry::instance().add(    \
        name,                                                   \
        description,                                            \
        &Class::declare_parameters,                             \
        [](const ::dealii::ParameterHandler &prm) {             \
          return std::unique_ptr<::tissuefem::time::Interface>( \
            std::make_unique<Class>(prm));                      \
        });                                                     \
      return true;                                              \
    }();                                                        \
  }
