#pragma once

#include <deal.II/base/point.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/base/parallel.h>

#include <vector>

namespace tissuefem::output
{
  using namespace dealii;

  /**
   * Point evaluation of a vector field at fixed reference points. The cell
   * containing each point and the point's reference coordinates are found
   * once (geometry::PointLocator: checked in the reference cell, also on
   * simplices), among the cells of all processes, whichever hold the whole
   * mesh or a part; the process owning that cell evaluates it as a sum over
   * the cell's shape functions.
   */
  template <int dim>
  class Probes
  {
  public:
    /// Throws InputError naming @p parameter if a point lies outside the mesh.
    Probes(const std::vector<Point<dim>> &points,
           const Mapping<dim>            &mapping,
           const DoFHandler<dim>         &dof_handler,
           const std::string             &parameter);

    const std::vector<Point<dim>> &
    points() const
    {
      return locations;
    }

    /// values[p][c]: component c of @p u at point p, on every process
    /// (@p u ghosted; the process owning the point's cell evaluates it).
    std::vector<Vector<double>>
    evaluate(const VectorType &u) const;

  private:
    std::vector<Point<dim>> locations;
    const DoFHandler<dim>  &dof_handler;
    /// The cell of each point, if this process owns it (else an invalid
    /// iterator).
    std::vector<typename DoFHandler<dim>::active_cell_iterator> cells;
    std::vector<Point<dim>> reference_points;
  };
} // namespace tissuefem::output
