// Fichera's corner and its 2D analogue: a re-entrant corner.
#include <deal.II/grid/grid_generator.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/geometry/source.h>

namespace tissuefem::geometry
{
  /**
   * The square or cube [a, b]^dim (a, b the first coordinates of 'Lower
   * corner' and 'Upper corner') without the quadrant or octant
   * [(a+b)/2, b]^dim, in 3 or 7 cells (deal.II's hyper_L): a re-entrant
   * corner where the stress is singular, for adaptive refinement.
   */
  template <int dim>
  class LShape : public Source<dim>
  {
  public:
    void
    build(const GeometryParameters &parameters,
          Triangulation<dim>       &triangulation) const override
    {
      require(dim > 1, "Geometry/Source", "'L-shape' needs 2 or 3 dimensions");
      const auto [lower, upper] = box_corners<dim>(parameters);
      require(upper[0] > lower[0],
              "Geometry/Upper corner",
              "must exceed 'Lower corner' in its first coordinate");
      if constexpr (dim > 1)
        GridGenerator::hyper_L(triangulation, lower[0], upper[0]);
    }
  };
} // namespace tissuefem::geometry

namespace
{
  using tissuefem::geometry::LShape;
}
TISSUEFEM_REGISTER_GEOMETRY_SOURCE(
  LShape,
  "L-shape",
  "(2D, 3D) the square or cube [a, b]^dim (a, b the first coordinates of "
  "the corners) without the quadrant or octant [(a+b)/2, b]^dim, in 3 or 7 "
  "cells (refine with 'Global refinements'): a re-entrant corner where the "
  "stress is singular; boundary ids from 'Boundary id predicates', as for "
  "files.")
