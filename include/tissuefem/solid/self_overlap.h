#pragma once

#include <deal.II/base/numbers.h>

#include <tissuefem/base/parallel.h>
#include <tissuefem/solid/discretization.h>

#include <array>
#include <utility>
#include <vector>

namespace tissuefem::solid
{
  /// The area vector of a straight boundary facet (2D: a segment, 3D: a
  /// triangle) with vertices @p x: its normal times its length (2D) or area
  /// (3D), pointing to the right of x0 -> x1 (2D) or by the right-hand rule
  /// (3D).
  template <int dim>
  Tensor<1, dim>
  oriented_area(const std::array<Point<dim>, dim> &x)
  {
    Tensor<1, dim> normal;
    if constexpr (dim == 2)
      {
        normal[0] = x[1][1] - x[0][1];
        normal[1] = x[0][0] - x[1][0];
      }
    if constexpr (dim == 3)
      normal = 0.5 * cross_product_3d(x[1] - x[0], x[2] - x[0]);
    return normal;
  }


  /**
   * Calls @p f(face, piece) for the straight facets of the boundary faces
   * of the locally owned cells (2D: the face; 3D: a triangle, or one of the
   * two triangles of a quadrilateral), @p piece the facet's vertices as
   * face vertex indices, ordered so that oriented_area() points out of the
   * reference body. The order of the calls is the order of
   * gather_boundary_facets().
   */
  template <int dim, typename Callback>
  void
  for_each_boundary_piece(const DoFHandler<dim> &dof_handler, const Callback &f)
  {
    if constexpr (dim == 1)
      return;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && cell->at_boundary())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            {
              // Triangles of the face (a quadrilateral's vertices are
              // numbered lexicographically: 0 1 3 and 0 3 2 go round).
              static constexpr unsigned int quadrilateral[2][3]
                = {{0, 1, 3}, {0, 3, 2}};
              const bool           split = dim == 3 && face->n_vertices() == 4;
              const Tensor<1, dim> out   = face->center() - cell->center();
              for (unsigned int p = 0; p < (split ? 2 : 1); ++p)
                {
                  std::array<unsigned int, dim> piece;
                  std::array<Point<dim>, dim>   X;
                  for (unsigned int k = 0; k < dim; ++k)
                    {
                      piece[k] = split ? quadrilateral[p][k] : k;
                      X[k]     = face->vertex(piece[k]);
                    }
                  // Orient by the reference normal.
                  if (oriented_area<dim>(X) * out < 0)
                    std::swap(piece[0], piece[1]);
                  f(face, piece);
                }
            }
  }


  /// The deformed boundary facets of the whole mesh, gathered on every
  /// process (for_each_boundary_piece(), dim points of dim coordinates
  /// each), and the index of this process's first.
  template <int dim>
  struct BoundaryFacets
  {
    std::vector<double> coordinates;
    unsigned int        first_local = 0;
  };

  /// The deformed boundary facets for the ghosted displacement @p u.
  template <int dim>
  BoundaryFacets<dim>
  gather_boundary_facets(const DoFHandler<dim> &dof_handler,
                         const VectorType      &u);

  /**
   * The generalized winding number of the closed boundary @p facets (as
   * BoundaryFacets::coordinates) around @p y: the sum of the signed solid
   * angles (2D: angles) under which the facets are seen from @p y, over
   * 4 pi (2 pi), leaving out facet @p skip (on whose plane @p y lies, where
   * its angle is undefined). 1 in the body, 0 outside, 1/2 on a flat piece
   * of its boundary (with that piece left out).
   */
  double
  winding_number(const Point<1>            &y,
                 const std::vector<double> &facets,
                 unsigned int skip = numbers::invalid_unsigned_int);
  double
  winding_number(const Point<2>            &y,
                 const std::vector<double> &facets,
                 unsigned int skip = numbers::invalid_unsigned_int);
  double
  winding_number(const Point<3>            &y,
                 const std::vector<double> &facets,
                 unsigned int skip = numbers::invalid_unsigned_int);


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
