#pragma once

#include <tissuefem/base/parallel.h>
#include <tissuefem/solid/discretization.h>

namespace tissuefem::solid
{
  /**
   * The share of the reference volume where the deformed body is tangled
   * (dimensionless, 0 to 1): cells with det F <= 0 at a quadrature point,
   * and cells whose deformed centre the deformed boundary winds around
   * other than once. The winding number is the generalized one: the sum of
   * the signed solid angles (in 2D, angles) under which the boundary
   * facets are seen from the point, over 4 pi (2 pi). A deformation that
   * is one to one with det F > 0 gives 0. A fold-over, where the body
   * overlaps itself with det F > 0 everywhere (an equilibrium of
   * elasticity alone, which no step control can leave), gives the cells
   * of the overlap, where the winding number is 2. An inverted element
   * inside the body can leave the winding number at 1 (two positive
   * coverings and one negative), which is why det F is asked too.
   *
   * From the vertices: cells and boundary facets are taken straight-sided
   * (quadrilateral facets as two triangles). The cost is (locally owned
   * cells) x (boundary facets of the whole mesh), which every process
   * gathers: meant for end-of-run reports, not for every step. In 1D: the
   * share with det F <= 0. @p u: ghosted displacement; the value is the
   * global one on every process.
   */
  template <int dim>
  double
  tangled_volume_fraction(const Discretization<dim> &discretization,
                          const VectorType          &u);
} // namespace tissuefem::solid
