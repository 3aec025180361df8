#include <deal.II/base/mpi.h>
#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/distributed/shared_tria.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/geometry/distribution.h>

#include <algorithm>

namespace tissuefem::geometry
{
  template <int dim>
  std::unique_ptr<parallel::TriangulationBase<dim>>
  make_parallel_mesh(const Distribution distribution)
  {
    const MPI_Comm comm = parallel_tools::communicator();
    if (distribution == Distribution::distributed)
      return std::make_unique<parallel::fullydistributed::Triangulation<dim>>(
        comm);
    // Artificial cells are not allowed: every process holds every cell.
    return std::make_unique<parallel::shared::Triangulation<dim>>(
      comm,
      Triangulation<dim>::limit_level_difference_at_vertices,
      /*allow_artificial_cells=*/false,
      parallel::shared::Triangulation<dim>::partition_metis);
  }


  template <int dim>
  void
  distribute(Triangulation<dim> &whole, parallel::TriangulationBase<dim> &mesh)
  {
    const MPI_Comm comm = parallel_tools::communicator();
    // The partition parallel::shared::Triangulation makes with
    // partition_metis, so both distributions give a process the same cells.
    GridTools::partition_triangulation(parallel_tools::n_processes(),
                                       whole,
                                       SparsityTools::Partitioner::metis);
    mesh.create_triangulation(
      TriangulationDescription::Utilities::
        create_description_from_triangulation(whole, comm));
  }


  template <int dim>
  bool
  holds_whole_mesh(const Triangulation<dim> &mesh)
  {
    return dynamic_cast<const parallel::fullydistributed::Triangulation<dim> *>(
             &mesh)
           == nullptr;
  }


  template <int dim>
  void
  require_whole_mesh(const Triangulation<dim> &mesh,
                     const std::string        &parameter,
                     const std::string        &what)
  {
    require(holds_whole_mesh(mesh),
            parameter,
            what
              + ", which needs every process to hold the whole mesh: set "
                "Geometry/Mesh distribution = shared");
  }


  template <int dim>
  double
  diameter(const Triangulation<dim> &mesh)
  {
    if (holds_whole_mesh(mesh))
      return GridTools::diameter(mesh);
    // Each process sends the boundary vertices of its own cells; a vertex
    // on a part's border may come from two processes, which does not
    // change a largest distance.
    std::vector<bool>       marked(mesh.n_vertices(), false);
    std::vector<Point<dim>> local;
    for (const auto &cell : mesh.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            for (const unsigned int v : face->vertex_indices())
              if (!marked[face->vertex_index(v)])
                {
                  marked[face->vertex_index(v)] = true;
                  local.push_back(face->vertex(v));
                }
    std::vector<Point<dim>> points;
    for (const auto &part :
         Utilities::MPI::all_gather(parallel_tools::communicator(), local))
      points.insert(points.end(), part.begin(), part.end());
    double largest = 0;
    for (std::size_t i = 0; i < points.size(); ++i)
      for (std::size_t j = i + 1; j < points.size(); ++j)
        largest = std::max(largest, points[i].distance(points[j]));
    return largest;
  }


#define TISSUEFEM_INSTANTIATE(dim)                                     \
  template std::unique_ptr<parallel::TriangulationBase<dim>>           \
                  make_parallel_mesh<dim>(Distribution);               \
  template void   distribute<dim>(Triangulation<dim> &,                \
                                parallel::TriangulationBase<dim> &); \
  template bool   holds_whole_mesh<dim>(const Triangulation<dim> &);   \
  template void   require_whole_mesh<dim>(const Triangulation<dim> &,  \
                                        const std::string &,         \
                                        const std::string &);        \
  template double diameter<dim>(const Triangulation<dim> &);
  TISSUEFEM_INSTANTIATE(1)
  TISSUEFEM_INSTANTIATE(2)
  TISSUEFEM_INSTANTIATE(3)
#undef TISSUEFEM_INSTANTIATE
} // namespace tissuefem::geometry
