#pragma once

#include <deal.II/distributed/tria_base.h>
#include <deal.II/grid/tria.h>

#include <memory>
#include <string>

namespace tissuefem::geometry
{
  using namespace dealii;

  /**
   * How the mesh of a run is spread over its MPI processes ('Geometry/Mesh
   * distribution'). Either way METIS gives each process a part of the cells
   * to assemble, and the same part for the same mesh and process count.
   *
   * - shared: every process holds every cell
   *   (parallel::shared::Triangulation). Whatever needs the whole mesh
   *   (tools that search vertices, the live view, adaptive refinement, a
   *   numerically differenced Jacobian) works.
   * - distributed: each process holds its own cells and the layer of cells
   *   around them (parallel::fullydistributed::Triangulation, which needs
   *   no p4est), so the mesh and its numbering no longer cost every process
   *   the whole mesh's memory. The whole mesh is built once on every
   *   process, checked, cut, and freed before any unknown is numbered.
   */
  enum class Distribution
  {
    shared,
    distributed
  };

  /// The empty mesh a run computes on, of the kind @p distribution names.
  template <int dim>
  std::unique_ptr<parallel::TriangulationBase<dim>>
  make_parallel_mesh(Distribution distribution);

  /**
   * Fills @p mesh, an empty parallel::fullydistributed::Triangulation, from
   * @p whole, the complete mesh, which every process built alike: METIS
   * partitions @p whole's active cells (as parallel::shared::Triangulation
   * does) and each process keeps its own cells and their neighbours. Ids,
   * refinement levels and vertex positions are kept.
   */
  template <int dim>
  void
  distribute(Triangulation<dim> &whole, parallel::TriangulationBase<dim> &mesh);

  /// Whether every process holds every cell of @p mesh (a serial mesh or a
  /// shared one).
  template <int dim>
  bool
  holds_whole_mesh(const Triangulation<dim> &mesh);

  /**
   * Throws InputError naming @p parameter unless every process holds the
   * whole of @p mesh: @p what (a sentence fragment) needs it.
   */
  template <int dim>
  void
  require_whole_mesh(const Triangulation<dim> &mesh,
                     const std::string        &parameter,
                     const std::string        &what);

  /**
   * The diameter of the reference body: the largest distance between two
   * of its boundary vertices, whichever processes hold them (as
   * GridTools::diameter() for a mesh held whole; collective).
   */
  template <int dim>
  double
  diameter(const Triangulation<dim> &mesh);
} // namespace tissuefem::geometry
