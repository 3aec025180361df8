#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <tissuefem/base/parallel.h>
#include <tissuefem/solid/discretization.h>

#include <boost/signals2/connection.hpp>

#include <cstdint>
#include <vector>

namespace tissuefem::contact
{
  using namespace dealii;

  /**
   * The quadrature points of the boundary faces of this process's cells,
   * where contact is evaluated, cached per mesh: their reference positions
   * X and area weights dA, each face's degrees of freedom, and the shape
   * functions' values there. The deformed positions x = X + u(X) for a
   * displacement then cost one small product per point, instead of an
   * FEFaceValues reinit per face per evaluation (measured on
   * liver_pressed.prm: contact took 55 % of the step through FEFaceValues).
   * Rebuilt on first use after the triangulation changes or the number of
   * degrees of freedom does (a renumbering of the same mesh is not seen:
   * TissueFEM numbers only after a mesh change).
   */
  template <int dim>
  class BoundaryPoints
  {
  public:
    explicit BoundaryPoints(const solid::Discretization<dim> &discretization);

    struct Face
    {
      /// (active cell index * faces per cell + face) * points per face:
      /// the first point's number, stable while the mesh is.
      std::uint64_t key;
      /// The cell's diameter (length units).
      double diameter;
      /// Its first point in points() and its first entry in dofs().
      unsigned int first_point, first_dof;
    };

    /// The faces, after rebuilding them if the mesh changed.
    const std::vector<Face> &
    faces() const;

    unsigned int
    points_per_face() const
    {
      return n_q;
    }

    unsigned int
    dofs_per_face() const
    {
      return n_dofs;
    }

    /// The degrees of freedom of @p face's cell.
    const types::global_dof_index *
    dofs(const Face &face) const
    {
      return &dof_indices[face.first_dof];
    }

    /// Reference position and area weight of point @p q of @p face.
    const Point<dim> &
    reference(const Face &face, const unsigned int q) const
    {
      return positions[face.first_point + q];
    }

    double
    weight(const Face &face, const unsigned int q) const
    {
      return weights[face.first_point + q];
    }

    /// The vector-valued shape function @p i of @p face's cell at its
    /// point @p q.
    Tensor<1, dim>
    shape(const Face &face, const unsigned int q, const unsigned int i) const
    {
      Tensor<1, dim> phi;
      phi[component[i]] = values[(face.first_point + q) * n_dofs + i];
      return phi;
    }

    /// The deformed positions x = X + u(X) of @p face's points, from the
    /// ghosted displacement @p u (one thread at a time: it reuses a
    /// buffer).
    void
    deformed(const Face              &face,
             const VectorType        &u,
             std::vector<Point<dim>> &x) const;

    /// The faces' degrees of freedom's values in the ghosted @p u (each
    /// once), the reference of motion_bound().
    void
    values_of(const VectorType &u, std::vector<double> &reference) const;

    /**
     * A bound on how far any point of any face has moved from where it was
     * at the displacement values_of() gave as @p reference to the ghosted
     * @p u (length units): sqrt(dim) L max_i |u_i - reference_i|, with L
     * the largest sum over one component's shape functions of |phi_i| at a
     * point (1 for linear elements, whose values are non-negative and sum
     * to 1). A few microseconds: one pass over the faces' values.
     */
    double
    motion_bound(const VectorType          &u,
                 const std::vector<double> &reference) const;

    /// Rebuilds the faces if the mesh changed, and finds where their
    /// entries lie in the layout of the ghosted @p u if it is new.
    void
    prepare(const VectorType &u) const;

    /// How many times the faces have been built or their entries found in
    /// a new layout: a change voids values_of()'s references and anything
    /// kept per face (call prepare() first).
    unsigned int
    generation() const
    {
      return builds;
    }

  private:
    void
    build() const;

    /// Finds local_index (and the distinct entries) for @p u's layout.
    void
    index(const VectorType &u) const;

    const solid::Discretization<dim> &discretization;
    unsigned int                      n_q = 0, n_dofs = 0;
    /// The component each shape function of a cell belongs to.
    std::vector<unsigned int> component;
    // The cache (built lazily, hence mutable).
    mutable bool                                 stale          = true;
    mutable types::global_dof_index              built_for_dofs = 0;
    mutable std::vector<Face>                    face_list;
    mutable std::vector<Point<dim>>              positions;
    mutable std::vector<double>                  weights;
    mutable std::vector<double>                  values;
    mutable std::vector<types::global_dof_index> dof_indices;
    /// Marks the cache stale when the mesh changes.
    boost::signals2::scoped_connection mesh_changed;
    /// Where each entry of dof_indices() lies in a ghosted vector's local
    /// entries (found on first use after a rebuild).
    mutable std::vector<int> local_index;
    /// The local length of the vector local_index was found in (another
    /// layout finds them anew).
    mutable int indexed_length = -1;
    /// The distinct entries of local_index, sorted.
    mutable std::vector<int> distinct_local;
    /// L of motion_bound(), and the number of builds.
    mutable double       lebesgue = 1;
    mutable unsigned int builds   = 0;
    /// deformed()'s buffer of a face's nodal values.
    mutable std::vector<double> local;
  };
} // namespace tissuefem::contact
