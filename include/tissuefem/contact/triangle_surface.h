#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <string>
#include <vector>

namespace tissuefem::contact
{
  using namespace dealii;

  /**
   * A closed, consistently oriented triangulated surface in 3D (an
   * instrument or an organ's neighbour exported from CAD or a segmentation)
   * with a signed-distance query.
   *
   * - Read from STL (ASCII or binary, told apart by the binary header's
   *   triangle count matching the file's size) or OBJ (polygons split into
   *   fans). STL's repeated vertices are merged where their coordinates are
   *   equal.
   * - Checked on construction: every edge bounds exactly two triangles
   *   that run it in opposite directions (closed and consistently
   *   oriented), no triangle has zero area; otherwise an InputError names
   *   the offending edges by their end points. A surface oriented inward
   *   (negative enclosed volume in every closed part) is turned outward;
   *   one whose parts disagree is refused.
   * - The query finds the nearest point by descending a bounding-volume
   *   tree (axis-aligned boxes, split at the median of the triangles'
   *   centroids along the longest side; Ericson 2005, chapter 6), pruning
   *   boxes farther than the best triangle so far; the nearest point on
   *   each triangle by Ericson 2005, section 5.1.5.
   * - The sign comes from the angle-weighted pseudonormal of the face, edge
   *   or vertex the nearest point lies on (Baerentzen and Aanaes 2005),
   *   which is right at every point, also beyond edges and corners.
   */
  class TriangleSurface
  {
  public:
    /// Where a point is with respect to the surface (see Gap in shape.h).
    struct Query
    {
      /// Signed distance (length units; positive outside).
      double distance = 0;
      /// The gradient of the signed distance: the face's normal, or the
      /// direction from the nearest edge or vertex point, outward.
      Tensor<1, 3> normal;
      /// d normal / dy (1 / length units): 0 beside a face, (I - n (x) n
      /// - e (x) e) / distance beside an edge of direction e, (I - n (x)
      /// n) / distance beside a vertex.
      Tensor<2, 3> normal_gradient;
      /// The nearest point of the surface.
      Point<3> foot;
    };

    /**
     * Reads @p file (.stl or .obj, by extension, in any case), coordinates
     * times @p scale. Errors name @p parameter and the file.
     */
    static TriangleSurface
    read(const std::string &file, const std::string &parameter, double scale);

    /// The surface of @p triangles (vertex indices into @p vertices);
    /// errors name @p what (the file, for messages).
    TriangleSurface(std::vector<Point<3>>                    vertices,
                    std::vector<std::array<unsigned int, 3>> triangles,
                    const std::string                       &what);

    /// The signed distance of @p y, through the tree.
    Query
    query(const Point<3> &y) const;

    /// The same by checking every triangle (for tests of the tree).
    Query
    query_all_triangles(const Point<3> &y) const;

    unsigned int
    n_triangles() const
    {
      return triangles.size();
    }

    /// Its corners and its triangles (indices into corners(), turned
    /// outwards).
    const std::vector<Point<3>> &
    corners() const
    {
      return vertices;
    }
    const std::vector<std::array<unsigned int, 3>> &
    faces() const
    {
      return triangles;
    }

    /// The volume enclosed (length^3 units, > 0).
    double
    volume() const;

  private:
    /// The nearest point on triangle @p t and where it lies: 0 inside the
    /// face, 1 + k at vertex k, 4 + k on edge k (from vertex k to k + 1).
    struct Candidate
    {
      double       distance_squared;
      Point<3>     foot;
      unsigned int triangle;
      unsigned int region;
    };

    Candidate
    nearest_on(const unsigned int t, const Point<3> &y) const;

    Query
    finish(const Point<3> &y, const Candidate &best) const;

    void
    check_and_orient(const std::string &what);

    /// Turns a surface oriented inward throughout; refuses one whose
    /// closed parts are oriented differently.
    void
    orient_parts(const std::string &what);

    void
    build_tree();

    struct Node
    {
      Point<3> lower, upper;
      /// Children (leaf: none), or the range [first, first + count) of
      /// tree_triangles.
      int          left = -1, right = -1;
      unsigned int first = 0, count = 0;
    };

    std::vector<Point<3>>                    vertices;
    std::vector<std::array<unsigned int, 3>> triangles;
    /// Unit normal of each triangle.
    std::vector<Tensor<1, 3>> face_normals;
    /// The pseudonormal of each triangle's edge k (the sum of its two
    /// triangles' normals) and of each vertex (angle-weighted).
    std::vector<std::array<Tensor<1, 3>, 3>> edge_normals;
    std::vector<Tensor<1, 3>>                vertex_normals;
    std::vector<Node>                        nodes;
    std::vector<unsigned int>                tree_triangles;
  };
} // namespace tissuefem::contact
