#include <deal.II/fe/mapping.h>

#include <tissuefem/geometry/point_locator.h>

#include <boost/geometry/index/rtree.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tissuefem::geometry
{
  template <int dim>
  PointLocator<dim>::PointLocator(const Mapping<dim>       &mapping,
                                  const Triangulation<dim> &mesh,
                                  const bool                owned_only)
      : mapping(mapping)
      , owned_only(owned_only)
  {
    std::vector<std::pair<BoundingBox<dim>, CellIterator>> cell_boxes;
    cell_boxes.reserve(mesh.n_active_cells());
    for (const auto &cell : mesh.active_cell_iterators())
      if (!cell->is_artificial() && (!owned_only || cell->is_locally_owned()))
        {
          // The mappings of the solid are linear (Q1, P1): a cell lies in the
          // box of its vertices. Enlarged so that a point just outside a
          // cell, within the tolerance, still finds it as a candidate.
          BoundingBox<dim> box  = mapping.get_bounding_box(cell);
          const double     size = box.get_boundary_points().first.distance(
            box.get_boundary_points().second);
          box.extend(4 * tolerance * size);
          cell_boxes.emplace_back(box, cell);
        }
    boxes = pack_rtree(cell_boxes);
  }


  template <int dim>
  double
  PointLocator<dim>::reference_cell_distance(const ReferenceCell &kind,
                                             const Point<dim>    &reference)
  {
    double outside = 0;
    if (kind == ReferenceCells::get_simplex<dim>())
      {
        // Barycentric coordinates: x_1, ..., x_dim and 1 - sum x_d.
        double last = 1;
        for (unsigned int d = 0; d < dim; ++d)
          {
            outside = std::max(outside, -reference[d]);
            last -= reference[d];
          }
        outside = std::max(outside, -last);
      }
    else
      {
        AssertThrow(kind == ReferenceCells::get_hypercube<dim>(),
                    ExcMessage("point location supports simplices and "
                               "hypercubes only"));
        for (unsigned int d = 0; d < dim; ++d)
          outside = std::max({outside, -reference[d], reference[d] - 1.});
      }
    // A NaN coordinate (an inverse mapping that failed quietly) is never
    // inside.
    return std::isnan(outside) ? std::numeric_limits<double>::infinity()
                               : outside;
  }


  template <int dim>
  std::optional<typename PointLocator<dim>::Location>
  PointLocator<dim>::locate(const Point<dim> &p) const
  {
    namespace bgi = boost::geometry::index;
    std::optional<Location> best;
    for (auto it = boxes.qbegin(bgi::intersects(p)); it != boxes.qend(); ++it)
      {
        const CellIterator &cell = it->second;
        Point<dim>          reference;
        try
          {
            reference = mapping.transform_real_to_unit_cell(cell, p);
          }
        catch (const typename Mapping<dim>::ExcTransformationFailed &)
          {
            // Far outside a distorted quadrilateral or hexahedron: the
            // inverse of its multilinear map may not exist there.
            continue;
          }
        const double outside
          = std::max(reference_cell_distance(cell->reference_cell(), reference),
                     0.);
        if (outside > tolerance)
          continue;
        if (!best
            || precedes(outside, cell->id(), best->outside, best->cell->id()))
          best = Location{cell, reference, outside};
      }
    return best;
  }

  template <int dim>
  bool
  PointLocator<dim>::precedes(const double  outside,
                              const CellId &id,
                              const double  best_outside,
                              const CellId &best_id)
  {
    // Deepest inside wins; points inside two cells (on a shared face, to
    // round-off) go to the lowest CellId, whatever the order of the
    // tree's answers or of the processes.
    return outside < best_outside || (outside == best_outside && id < best_id);
  }


  template <int dim>
  typename PointLocator<dim>::Found
  PointLocator<dim>::locate_among_processes(const Point<dim> &p,
                                            const MPI_Comm    comm) const
  {
    // Candidates of cells a process does not own would be found twice.
    Assert(owned_only, ExcMessage("build the locator with owned_only"));
    const auto found = locate(p);
    // (how far outside, CellId as text) of each process's own candidate.
    const std::pair<double, std::string> mine(found ? found->outside : 0.,
                                              found
                                                ? found->cell->id().to_string()
                                                : std::string());
    std::optional<std::pair<double, CellId>> best;
    for (const auto &[outside, id] : Utilities::MPI::all_gather(comm, mine))
      if (!id.empty()
          && (!best
              || precedes(outside, CellId(id), best->first, best->second)))
        best = std::pair(outside, CellId(id));
    Found result;
    result.anywhere = best.has_value();
    if (found && best && found->cell->id() == best->second)
      result.here = found;
    return result;
  }


  template class PointLocator<1>;
  template class PointLocator<2>;
  template class PointLocator<3>;
} // namespace tissuefem::geometry
