#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/grid/tria.h>

#include <tissuefem/geometry/distribution.h>

#include <string>

namespace tissuefem::geometry
{
  using namespace dealii;

  /**
   * The 'Geometry' subsection: where the reference configuration comes from
   * (a deal.II generator or a mesh file), its cell type, refinement and
   * boundary ids.
   */
  struct GeometryParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /// Makes a relative 'Mesh file' relative to @p directory (the
    /// parameter file's).
    void
    resolve_relative_to(const std::string &directory);

    std::string source;    ///< a registered Source (geometry/source.h)
    std::string cell_type; ///< "hypercube" or "simplex"
    std::string lower_corner, upper_corner, subdivisions, corners;
    /// 'Tetrahedra per hexahedron' of a simplex box in 3D: 5 or 6
    unsigned int tetrahedra_per_hexahedron = 5;
    double       grading;       ///< 'Grading': finer at graded_toward
    std::string  graded_toward; ///< 'Graded toward': a point, or empty
    std::string  mesh_file;
    double       scale;
    unsigned int global_refinements;
    std::string  boundary_id_predicates;
    std::string  material_id_predicates;
    /// 'Mesh distribution': how the mesh is spread over processes
    Distribution distribution = Distribution::shared;
  };

  /**
   * Builds the reference configuration. A generated box has boundary ids
   * 0/1 on the faces x = lower/upper, 2/3 on y, 4/5 on z, and material id 0.
   * Meshes read from a file keep the ids the file carries (0 where it
   * carries none). Then each 'Boundary id predicates' entry "id: expression"
   * assigns its id to every boundary face whose centre satisfies the
   * muparser expression of x, y, z, in the order given, and likewise
   * 'Material id predicates' for cell centres. Throws InputError on any
   * problem.
   */
  template <int dim>
  void
  build_triangulation(const GeometryParameters &parameters,
                      Triangulation<dim>       &triangulation);

  /// The id that boundary faces of a mesh file get when 'Boundary id
  /// predicates' is given and none of them matches (see its documentation).
  constexpr types::boundary_id unmatched_boundary_id = 254;

  /// "boundary faces by id: 0 (12) 1 (12) ...": how many boundary faces
  /// carry each id (in the whole mesh, whichever processes hold it;
  /// collective on a parallel mesh).
  template <int dim>
  std::string
  describe_boundary_ids(const Triangulation<dim> &triangulation);

  /// Whether the triangulation's cells are simplices (triangles, tets).
  template <int dim>
  bool
  is_simplex_mesh(const Triangulation<dim> &triangulation);
} // namespace tissuefem::geometry
