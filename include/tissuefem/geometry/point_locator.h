#pragma once

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/reference_cell.h>
#include <deal.II/grid/tria.h>
#include <deal.II/numerics/rtree.h>

#include <optional>
#include <utility>
#include <vector>

namespace tissuefem::geometry
{
  using namespace dealii;

  /**
   * Where a point of the reference configuration lies: the active cell
   * that contains it and its coordinates in that cell's reference cell.
   * The one service for probes, tools and anything else that asks.
   *
   * Why not GridTools::find_active_cell_around_point: in deal.II 9.4 its
   * search works for hypercube meshes only (deal.II issue 14704, fixed by
   * pull requests 15808/15811 after 9.5 and moved to 9.5.x by 16658;
   * doc/references.md), so a point near a face of a tetrahedron can be
   * given to a neighbour and extrapolated there: probe values 5-30 % off
   * on SOFA's liver, errors of the order of the field itself in
   * unit/point_location.
   *
   * Here the candidates are the cells whose bounding box (slightly
   * enlarged) contains the point, found in an R-tree; each is checked in
   * its own reference cell (reference_cell_distance()); the candidate the
   * point is deepest inside wins, a tie (a point on a shared face) going
   * to the lowest CellId, which names a cell alike on every process and
   * for every partition (active cell indices are a process's own on a
   * distributed mesh). Built for the current mesh: rebuild it when the
   * mesh changes.
   */
  template <int dim>
  class PointLocator
  {
  public:
    using CellIterator = typename Triangulation<dim>::active_cell_iterator;

    struct Location
    {
      CellIterator cell;
      /// Coordinates of the point in the reference cell of @p cell.
      Point<dim> reference;
      /// How far it lies outside that cell (reference_cell_distance(), at
      /// least 0, at most tolerance).
      double outside;
    };

    /// How far outside its reference cell a point may be and still count
    /// as inside (reference units: edges of length 1): round-off of the
    /// inverse mapping, and points on the mesh's boundary.
    static constexpr double tolerance = 1e-10;

    /// Searches the active cells of @p mesh this process holds, or, if
    /// @p owned_only, those it owns.
    PointLocator(const Mapping<dim>       &mapping,
                 const Triangulation<dim> &mesh,
                 bool                      owned_only = false);

    /// The cell containing @p p, or nothing if no cell does (within
    /// tolerance).
    std::optional<Location>
    locate(const Point<dim> &p) const;

    /// What locate_among_processes() found.
    struct Found
    {
      /// Whether a cell of any process contains the point.
      bool anywhere = false;
      /// Where, if this process owns that cell.
      std::optional<Location> here;
    };

    /**
     * Collective over @p comm: the cell containing @p p among the cells
     * the processes own, chosen by locate()'s rule over all of them, so
     * the same cell whichever cells each process holds. For a locator
     * built with owned_only.
     */
    Found
    locate_among_processes(const Point<dim> &p, const MPI_Comm comm) const;

    /**
     * How far @p reference lies outside the reference cell @p kind, in
     * reference units (0 inside): on simplices the most negative
     * barycentric coordinate, on hypercubes the largest excess of a
     * coordinate beyond [0, 1].
     */
    static double
    reference_cell_distance(const ReferenceCell &kind,
                            const Point<dim>    &reference);

  private:
    /// The rule of locate(): whether the candidate cell @p id, which the
    /// point lies @p outside of, beats the best so far, @p best_id at
    /// @p best_outside.
    static bool
    precedes(double        outside,
             const CellId &id,
             double        best_outside,
             const CellId &best_id);

    const Mapping<dim> &mapping;
    /// Whether only the cells this process owns were taken.
    const bool                                       owned_only;
    RTree<std::pair<BoundingBox<dim>, CellIterator>> boxes;
  };
} // namespace tissuefem::geometry
