#pragma once

#include <deal.II/base/point.h>
#include <deal.II/grid/tria.h>

#include <vector>

namespace tissuefem::geometry
{
  using namespace dealii;

  /**
   * The face-connected parts of a mesh: cells that share a face (through
   * hanging faces too) belong to the same part. Parts that touch only at
   * a vertex or an edge are separate: such a joint is a hinge, not a hold.
   */
  template <int dim>
  struct MeshParts
  {
    /// Finds the parts of the active cells of @p triangulation (all of
    /// them: it must hold every cell, as a shared triangulation does).
    explicit MeshParts(const Triangulation<dim> &triangulation);

    unsigned int
    n_parts() const
    {
      return first_cell.size();
    }

    /// The part of each active cell, by active_cell_index(); parts are
    /// numbered in the order of their first cell.
    std::vector<unsigned int> part_of_cell;
    /// Per part: the active_cell_index() of its first cell, and that
    /// cell's centre (to name the part in a message).
    std::vector<unsigned int> first_cell;
    std::vector<Point<dim>>   a_point;
  };
} // namespace tissuefem::geometry
