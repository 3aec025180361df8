#pragma once

#include <tissuefem/base/parallel.h>

namespace tissuefem::solid
{
  /**
   * Unknowns of an operator that Newton's method updates alongside the
   * displacement but that are not in its vector: the cell dilatations and
   * pressures of the three-field mean dilatation element
   * (ThreeFieldDilatation). Within one implicit step the integrator calls
   * begin_iterations() before the step's first assembly, predict_update()
   * after every linear solve, set_step_length() before every evaluation
   * along an update, and end_iterations() when Newton is done; between steps
   * the operator is condensed again, so no state outlives a step (nothing to
   * checkpoint or move to a new mesh).
   */
  class IterationUnknowns
  {
  public:
    virtual ~IterationUnknowns() = default;

    /// The next assembly sets the unknowns from the displacement it is
    /// given (and from a dilatation carried across a mesh change,
    /// DilatationCarry, at @p start_time, the step's start).
    virtual void
    begin_iterations(const double start_time)
      = 0;

    /// Their increments for the displacement update @p du (with the
    /// linearization of the last Jacobian assembled).
    virtual void
    predict_update(const VectorType &du)
      = 0;

    /// Sets them to their value at step length @p alpha along the last
    /// prediction (0: where the prediction started).
    virtual void
    set_step_length(const double alpha)
      = 0;

    /// Back to the condensed operator; @p converged: the step succeeded
    /// (what was carried across a mesh change has served).
    virtual void
    end_iterations(const bool converged)
      = 0;

    /// Whether between begin_iterations() and end_iterations().
    virtual bool
    iterating() const = 0;
  };
} // namespace tissuefem::solid
