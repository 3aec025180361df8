#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/grid/tria.h>

#include <tissuefem/adaptation/indicator.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/solid/solid.h>

#include <memory>
#include <string>
#include <vector>

namespace tissuefem::adaptation
{
  using namespace dealii;

  /// The 'Mesh refinement' subsection.
  struct MeshRefinementParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    std::string  indicator;
    std::string  strategy;
    double       refine_fraction;
    double       coarsen_fraction;
    unsigned int interval;
    unsigned int max_levels;
    unsigned int max_cells;
  };

  /**
   * Adaptive refinement and coarsening during a run: every 'Interval'
   * steps, a registered error indicator per cell (Indicator) marks cells by a
   * fixed fraction of the total indicator or a fixed number of cells, within
   * bounds on levels and cell count; the mesh changes identically on every
   * process (the indicator is summed over processes first), the solid is set up
   * anew (hanging-node constraints included) and every given vector is
   * interpolated to the new mesh. Quadrilaterals and hexahedra only:
   * deal.II 9.4 cannot refine simplex meshes locally (no hanging nodes on
   * simplices).
   */
  template <int dim>
  class MeshAdaptation
  {
  public:
    MeshAdaptation(const MeshRefinementParameters &parameters,
                   Triangulation<dim>             &triangulation,
                   solid::Solid<dim>              &solid);

    /// Whether refinement is switched on.
    bool
    enabled() const
    {
      return parameters.indicator != "none";
    }

    /// Whether to adapt after step @p step.
    bool
    due(const unsigned int step) const
    {
      return enabled() && step % parameters.interval == 0;
    }

    /**
     * Marks cells from the indicator of @p u, changes the mesh, sets the
     * solid up on it and interpolates every vector of @p vectors (owned
     * layout, replaced by vectors on the new mesh; @p u among them). For
     * a formulation that carries cell dilatations (the mean dilatation),
     * they are carried to the new mesh and released over its release steps
     * ('Materials/Mean dilatation/Release steps') times @p time_step
     * (solid/dilatation_carry.h). Returns whether the mesh
     * changed.
     */
    bool
    adapt(const VectorType                &u,
          const double                     time,
          const double                     time_step,
          const std::vector<VectorType *> &vectors);

  private:
    MeshRefinementParameters parameters;
    Triangulation<dim>      &triangulation;
    solid::Solid<dim>       &solid;
    unsigned int             initial_level;
    /// The indicator named by 'Indicator' (null for 'none').
    std::unique_ptr<Indicator<dim>> estimator;
  };
} // namespace tissuefem::adaptation
