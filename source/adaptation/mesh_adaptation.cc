#include <deal.II/base/quadrature_lib.h>
#include <deal.II/grid/grid_refinement.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/solution_transfer.h>

#include <tissuefem/adaptation/indicator.h>
#include <tissuefem/adaptation/mesh_adaptation.h>
#include <tissuefem/base/input_error.h>
#include <tissuefem/geometry/distribution.h>

#include <algorithm>

namespace tissuefem::adaptation
{
  void
  MeshRefinementParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mesh refinement");
    // The choices are the registered indicators (adaptation/indicator.h),
    // one file each; the same in every dimension.
    const auto &indicators = IndicatorRegistry<2>::instance();
    prm.declare_entry(
      "Indicator",
      "none",
      Patterns::Selection("none|" + indicators.selection_pattern()),
      "'none': the mesh stays as built. Otherwise the mesh adapts during "
      "the run from the named indicator (quadrilaterals/hexahedra only: "
      "deal.II 9.4 cannot refine simplices locally): "
        + indicators.documentation());
    prm.declare_entry("Strategy",
                      "fixed number",
                      Patterns::Selection("fixed number|fixed fraction"),
                      "'fixed number': refine the 'Refine fraction' share of "
                      "cells with the largest indicators and coarsen the "
                      "'Coarsen fraction' share with the smallest. 'fixed "
                      "fraction': refine the cells with the largest "
                      "indicators that together hold 'Refine fraction' of "
                      "the total, coarsen those holding 'Coarsen fraction'.");
    prm.declare_entry("Refine fraction",
                      "0.3",
                      Patterns::Double(0, 1),
                      "Share of cells (fixed number) or of the summed "
                      "indicator (fixed fraction) to refine; in [0, 1].");
    prm.declare_entry("Coarsen fraction",
                      "0.03",
                      Patterns::Double(0, 1),
                      "Share to coarsen, as 'Refine fraction'; refine plus "
                      "coarsen fraction must be at most 1.");
    prm.declare_entry("Interval",
                      "1",
                      Patterns::Integer(1),
                      "Adapt after every this many time (or load) steps.");
    prm.declare_entry("Maximum levels",
                      "2",
                      Patterns::Integer(0, 10),
                      "Refinement levels allowed above the mesh the run "
                      "starts with (cells are never coarsened below it).");
    prm.declare_entry("Maximum cells",
                      "0",
                      Patterns::Integer(0),
                      "Stop refining when the mesh would exceed about this "
                      "many cells; 0: no limit.");
    prm.leave_subsection();
  }


  void
  MeshRefinementParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mesh refinement");
    indicator        = prm.get("Indicator");
    strategy         = prm.get("Strategy");
    refine_fraction  = prm.get_double("Refine fraction");
    coarsen_fraction = prm.get_double("Coarsen fraction");
    interval         = prm.get_integer("Interval");
    max_levels       = prm.get_integer("Maximum levels");
    max_cells        = prm.get_integer("Maximum cells");
    prm.leave_subsection();
    require(refine_fraction + coarsen_fraction <= 1,
            "Mesh refinement/Coarsen fraction",
            "plus 'Refine fraction' must be at most 1");
  }


  template <int dim>
  MeshAdaptation<dim>::MeshAdaptation(
    const MeshRefinementParameters &parameters,
    Triangulation<dim>             &triangulation,
    solid::Solid<dim>              &solid)
      : parameters(parameters)
      , triangulation(triangulation)
      , solid(solid)
      , initial_level(triangulation.n_global_levels() - 1)
  {
    if (!enabled())
      return;
    require(!solid.get_discretization().simplex,
            "Mesh refinement/Indicator",
            "adaptive refinement needs quadrilaterals/hexahedra: deal.II "
            "9.4 cannot refine triangles/tetrahedra locally (use 'none', "
            "or 'Geometry/Global refinements' for uniform refinement)");
    // A fully distributed mesh of deal.II 9.4 cannot be refined.
    geometry::require_whole_mesh(triangulation,
                                 "Mesh refinement/Indicator",
                                 "adaptive refinement");
    estimator = IndicatorRegistry<dim>::instance().create(parameters.indicator);
  }


  template <int dim>
  bool
  MeshAdaptation<dim>::adapt(const VectorType                &u,
                             const double                     time,
                             const double                     time_step,
                             const std::vector<VectorType *> &vectors)
  {
    const auto    &discretization = solid.get_discretization();
    const auto    &dof_handler    = discretization.dof_handler;
    const MPI_Comm comm           = parallel_tools::communicator();

    // The indicator on this process's cells, summed over processes so that
    // every process marks the same cells.
    VectorType ghosted;
    discretization.initialize_vector(ghosted, true);
    ghosted = u;
    Vector<float> indicator(triangulation.n_active_cells());
    estimator->estimate(solid, ghosted, time, indicator);
    Utilities::MPI::sum(indicator, comm, indicator);

    const unsigned int max_cells = parameters.max_cells > 0
                                     ? parameters.max_cells
                                     : std::numeric_limits<unsigned int>::max();
    if (parameters.strategy == "fixed number")
      GridRefinement::refine_and_coarsen_fixed_number(
        triangulation,
        indicator,
        parameters.refine_fraction,
        parameters.coarsen_fraction,
        max_cells);
    else
      GridRefinement::refine_and_coarsen_fixed_fraction(
        triangulation,
        indicator,
        parameters.refine_fraction,
        parameters.coarsen_fraction,
        max_cells);
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        if (cell->level()
            >= static_cast<int>(initial_level + parameters.max_levels))
          cell->clear_refine_flag();
        if (cell->level() <= static_cast<int>(initial_level))
          cell->clear_coarsen_flag();
      }
    triangulation.prepare_coarsening_and_refinement();
    bool flagged = false;
    for (const auto &cell : triangulation.active_cell_iterators())
      flagged = flagged || cell->refine_flag_set() || cell->coarsen_flag_set();
    if (!flagged)
      return false;

    // Every process holds the whole mesh, so each interpolates whole
    // (replicated) vectors; then keeps the entries it owns.
    std::vector<Vector<double>> old_values(vectors.size());
    for (unsigned int k = 0; k < vectors.size(); ++k)
      {
        // Hanging values exactly as the constraints compute them, so that
        // the interpolation from either side of a refined edge agrees.
        discretization.hanging_node_constraints.distribute(*vectors[k]);
        old_values[k] = *vectors[k];
      }
    const auto u_index = std::find(vectors.begin(), vectors.end(), &u);
    AssertThrow(u_index != vectors.end(),
                ExcMessage("adapt(): u must be among the vectors"));
    const unsigned int                 u_k     = u_index - vectors.begin();
    solid::DilatationCarry<dim> *const carried = solid.dilatation_carry();
    const bool carry = carried && carried->release_steps > 0;
    if (carry)
      carried->record(dof_handler,
                      *discretization.mapping,
                      discretization.cell_quadrature,
                      old_values[u_k],
                      time);
    SolutionTransfer<dim, Vector<double>> transfer(dof_handler);
    transfer.prepare_for_coarsening_and_refinement(old_values);
    triangulation.execute_coarsening_and_refinement();
    // The state moves to the new mesh first among those told of the
    // change, so that they all see it there.
    const boost::signals2::scoped_connection transfer_state
      = solid.signals.changed.connect(
        [&]() {
          std::vector<Vector<double>> new_values(
            vectors.size(), Vector<double>(dof_handler.n_dofs()));
          transfer.interpolate(old_values, new_values);
          for (unsigned int k = 0; k < vectors.size(); ++k)
            {
              solid.initialize_vector(*vectors[k]);
              for (const auto i : discretization.locally_owned)
                (*vectors[k])[i] = new_values[k][i];
              vectors[k]->compress(VectorOperation::insert);
              discretization.hanging_node_constraints.distribute(*vectors[k]);
            }
          // Before anyone else assembles on the new mesh.
          if (!carry)
            {
              if (carried)
                carried->clear();
              return;
            }
          Vector<double> u_new;
          u_new = *vectors[u_k];
          carried->finish(dof_handler,
                          *discretization.mapping,
                          discretization.cell_quadrature,
                          u_new,
                          time,
                          carried->release_steps * time_step);
        },
        boost::signals2::at_front);
    solid.setup();
    return true;
  }

  template class MeshAdaptation<1>;
  template class MeshAdaptation<2>;
  template class MeshAdaptation<3>;
} // namespace tissuefem::adaptation
