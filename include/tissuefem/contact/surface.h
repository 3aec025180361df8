#pragma once

#include <tissuefem/contact/shape.h>
#include <tissuefem/contact/triangle_surface.h>

#include <memory>
#include <string>

namespace tissuefem::contact
{
  /**
   * A closed triangulated surface read from STL or OBJ (an instrument's
   * jaw, a bone, a neighbouring organ), 3D only: the signed distance, its
   * normal and the normal's gradient from TriangleSurface (a bounding-volume
   * tree over its triangles, angle-weighted pseudonormals for the sign).
   * Beside a face it acts as a plane; beyond an edge or a vertex the
   * distance field is rounded, with its curvature in the tangent.
   */
  template <int dim>
  class Surface : public Shape<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    /// Reads 'surface/File', a relative path taken from @p directory (the
    /// parameter file's).
    Surface(ParameterHandler &prm, const std::string &directory);

    Gap<dim>
    gap(const Point<dim> &y) const override;

    Drawing<dim>
    drawing(const Point<dim> &centre, const double extent) const override;

    /// The triangulated surface, for tests and statistics.
    const TriangleSurface &
    triangles() const
    {
      return *surface;
    }

  private:
    std::shared_ptr<const TriangleSurface> surface;
  };
} // namespace tissuefem::contact
