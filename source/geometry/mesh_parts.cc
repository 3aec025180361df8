#include <tissuefem/geometry/mesh_parts.h>

#include <numeric>

namespace tissuefem::geometry
{
  namespace
  {
    /// The root of @p i in a union-find forest (with path halving).
    unsigned int
    root(std::vector<unsigned int> &parent, unsigned int i)
    {
      while (parent[i] != i)
        i = parent[i] = parent[parent[i]];
      return i;
    }
  } // namespace


  template <int dim>
  MeshParts<dim>::MeshParts(const Triangulation<dim> &triangulation)
  {
    const unsigned int        n = triangulation.n_active_cells();
    std::vector<unsigned int> parent(n);
    std::iota(parent.begin(), parent.end(), 0u);
    // A face to a refined neighbour is seen from the neighbour's children,
    // whose neighbour across it is this (active) cell; so joining active
    // neighbours only joins every face-sharing pair.
    for (const auto &cell : triangulation.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (!cell->at_boundary(f) && cell->neighbor(f)->is_active())
          {
            const unsigned int a = root(parent, cell->active_cell_index());
            const unsigned int b
              = root(parent, cell->neighbor(f)->active_cell_index());
            if (a != b)
              parent[std::max(a, b)] = std::min(a, b);
          }

    part_of_cell.assign(n, 0);
    std::vector<unsigned int> part_of_root(n, n);
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        const unsigned int i = cell->active_cell_index();
        unsigned int      &p = part_of_root[root(parent, i)];
        if (p == n)
          {
            p = first_cell.size();
            first_cell.push_back(i);
            a_point.push_back(cell->center());
          }
        part_of_cell[i] = p;
      }
  }

  template struct MeshParts<1>;
  template struct MeshParts<2>;
  template struct MeshParts<3>;
} // namespace tissuefem::geometry
