#pragma once

#include <tissuefem/base/parallel.h>
#include <tissuefem/boundary/manufactured_solution.h>
#include <tissuefem/postprocess/interface.h>
#include <tissuefem/solid/discretization.h>

namespace tissuefem::postprocess
{
  /// Errors of a discrete displacement against the manufactured one at a
  /// time (length units; the H1 seminorm error is dimensionless per unit
  /// volume^(1/2)).
  struct ManufacturedErrors
  {
    /// ||u_h - u||_L2, ||Grad (u_h - u)||_L2, and ||u||_L2, ||Grad u||_L2
    /// for relative errors.
    double l2, h1, l2_exact, h1_exact;
  };

  /// The errors of the ghosted @p u_ghosted on @p discretization against
  /// @p exact at time @p t: Gauss quadrature with two more points per
  /// direction than the element needs, summed over the processes.
  template <int dim>
  ManufacturedErrors
  manufactured_errors(const boundary::ManufacturedSolution<dim> &exact,
                      const solid::Discretization<dim>          &discretization,
                      const VectorType                          &u_ghosted,
                      const double                               t);

  /**
   * With 'Manufactured solution/Enabled': the error of every state against
   * the exact displacement. run.txt gets the final L2 error (length units)
   * and H1 seminorm error, their relative values, the largest L2 error over
   * the steps, the L2(0,T; L2) error (sum over steps of dt ||u_h - u||^2)^(1/2)
   * and, on hypercube meshes, the stress-jump error estimate and its
   * effectivity; the screen a one-line report.
   */
  template <int dim>
  class ManufacturedError : public Interface<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &)
    {
    }

    explicit ManufacturedError(ParameterHandler &)
    {
    }


    std::vector<std::string>
    save() const override;

    void
    restore(const std::vector<std::string> &lines) override;

    void
    execute(const Step<dim> &step) override;

    void
    finish(const time::State &state,
           const RunTotals   &totals,
           output::RunRecord &record) override;

  private:
    double             max_l2 = 0, l2_time_integral = 0, last_time = 0;
    ManufacturedErrors last{0, 0, 0, 0};
  };
} // namespace tissuefem::postprocess
