#pragma once

#include <deal.II/grid/tria.h>

#include <tissuefem/base/registry.h>
#include <tissuefem/geometry/geometry.h>

#include <memory>
#include <string>
#include <utility>

namespace tissuefem::geometry
{
  /**
   * Where a reference configuration comes from: a generator or a mesh
   * reader, named by 'Geometry/Source'. Each is one class in one file,
   * registered with TISSUEFEM_REGISTER_GEOMETRY_SOURCE, so that the choice
   * lists what is compiled in. build_triangulation() calls it, then
   * refines and applies the id predicates.
   */
  template <int dim>
  class Source
  {
  public:
    virtual ~Source() = default;

    /// Builds the unrefined mesh; throws InputError naming the parameter
    /// at fault.
    virtual void
    build(const GeometryParameters &parameters,
          Triangulation<dim>       &triangulation) const = 0;

    /// Whether the faces come with meaningful boundary ids (a generated
    /// box), so that 'Boundary id predicates' only overrides them. Where
    /// they do not (a file, the L-shape), faces no predicate matches get
    /// unmatched_boundary_id.
    virtual bool
    faces_carry_ids() const
    {
      return false;
    }
  };

  template <int dim>
  using SourceRegistry = Registry<Source<dim>>;

  /// 'Lower corner' and 'Upper corner' (for generated meshes).
  template <int dim>
  std::pair<Point<dim>, Point<dim>>
  box_corners(const GeometryParameters &parameters);
} // namespace tissuefem::geometry

/// Registers a geometry source at the end of its source file.
#define TISSUEFEM_REGISTER_GEOMETRY_SOURCE(Class, name, description) \
  namespace                                                          \
  {                                                                  \
    const bool tissuefem_registered_##Class                          \
      = ::tissuefem::register_in_every_dimension<                    \
        ::tissuefem::geometry::Source,                               \
        Class>(name, description);                                   \
  }
