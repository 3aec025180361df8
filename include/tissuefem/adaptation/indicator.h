#pragma once

#include <deal.II/lac/vector.h>

#include <tissuefem/base/registry.h>
#include <tissuefem/solid/solid.h>

#include <memory>
#include <string>

namespace tissuefem::adaptation
{
  using namespace dealii;

  /**
   * A refinement indicator: a non-negative number per active cell saying
   * how much refining the cell would gain. MeshAdaptation sums the values
   * over processes and marks cells from them. Each indicator is one class
   * in one file, registered with TISSUEFEM_REGISTER_INDICATOR, so that
   * 'Mesh refinement/Indicator' lists what is compiled in.
   */
  template <int dim>
  class Indicator
  {
  public:
    virtual ~Indicator() = default;

    /// Fills @p indicator (one entry per active cell, by active cell
    /// index) on this process's cells, zero elsewhere, for the ghosted
    /// displacement @p u_ghosted at @p time.
    virtual void
    estimate(const solid::Solid<dim> &solid,
             const VectorType        &u_ghosted,
             const double             time,
             Vector<float>           &indicator) const = 0;
  };

  template <int dim>
  using IndicatorRegistry = Registry<Indicator<dim>>;
} // namespace tissuefem::adaptation

/// Registers a refinement indicator at the end of its source file.
#define TISSUEFEM_REGISTER_INDICATOR(Class, name, description) \
  namespace                                                    \
  {                                                            \
    const bool tissuefem_registered_##Class                    \
      = ::tissuefem::register_in_every_dimension<              \
        ::tissuefem::adaptation::Indicator,                    \
        Class>(name, description);                             \
  }
