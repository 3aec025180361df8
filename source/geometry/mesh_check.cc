#include <deal.II/grid/grid_tools.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/geometry/mesh_check.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

namespace tissuefem::geometry
{
  namespace
  {
    /// "ids 3, 17, 20 (and 4 more)".
    std::string
    first_few(const std::vector<unsigned int> &ids)
    {
      std::ostringstream text;
      for (unsigned int i = 0; i < ids.size() && i < 5; ++i)
        text << (i ? ", " : "") << ids[i];
      if (ids.size() > 5)
        text << " (and " << ids.size() - 5 << " more)";
      return text.str();
    }

    /// The smallest Jacobian determinant at the vertices of a cell, times
    /// the reference measure: signed volume for simplices.
    template <int dim>
    double
    smallest_vertex_jacobian(
      const typename Triangulation<dim>::active_cell_iterator &cell)
    {
      if (dim == 1)
        return cell->vertex(1)[0] - cell->vertex(0)[0];
      if (cell->reference_cell().is_simplex())
        {
          Tensor<2, dim> edges;
          for (unsigned int d = 0; d < dim; ++d)
            edges[d] = cell->vertex(d + 1) - cell->vertex(0);
          return determinant(edges);
        }
      // Hypercube: at each vertex the edges to its dim neighbours along
      // the coordinate directions of the reference cell (vertex v's
      // neighbour in direction d is v xor 2^d), oriented by the vertex's
      // position.
      double smallest = std::numeric_limits<double>::max();
      for (unsigned int v = 0; v < cell->n_vertices(); ++v)
        {
          Tensor<2, dim> edges;
          double         sign = 1;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const unsigned int w = v ^ (1u << d);
              edges[d]             = cell->vertex(w) - cell->vertex(v);
              if (v & (1u << d))
                sign = -sign;
            }
          smallest = std::min(smallest, sign * determinant(edges));
        }
      return smallest;
    }
  } // namespace


  template <int dim>
  void
  check_mesh(const Triangulation<dim> &triangulation, const std::string &file)
  {
    const std::string         where    = "Mesh file '" + file + "': ";
    const auto               &vertices = triangulation.get_vertices();
    const auto                used     = triangulation.get_used_vertices();
    std::vector<unsigned int> bad;
    for (unsigned int v = 0; v < vertices.size(); ++v)
      if (used[v])
        for (unsigned int d = 0; d < dim; ++d)
          if (!std::isfinite(vertices[v][d]))
            {
              bad.push_back(v);
              break;
            }
    if (!bad.empty())
      throw InputError(where
                       + "vertices with coordinates that are not "
                         "finite numbers: ids "
                       + first_few(bad));

    // Duplicates: sort by the first coordinate, compare within a window.
    const double              extent    = GridTools::diameter(triangulation);
    const double              tolerance = 1e-10 * extent;
    std::vector<unsigned int> order;
    for (unsigned int v = 0; v < vertices.size(); ++v)
      if (used[v])
        order.push_back(v);
    std::sort(order.begin(), order.end(), [&](unsigned int a, unsigned int b) {
      return vertices[a][0] < vertices[b][0];
    });
    for (unsigned int i = 0; i < order.size(); ++i)
      for (unsigned int j = i + 1;
           j < order.size()
           && vertices[order[j]][0] - vertices[order[i]][0] <= tolerance;
           ++j)
        if (vertices[order[i]].distance(vertices[order[j]]) <= tolerance)
          {
            bad.push_back(std::min(order[i], order[j]));
            bad.push_back(std::max(order[i], order[j]));
          }
    if (!bad.empty())
      throw InputError(where
                       + "duplicate vertices (distinct nodes at the "
                         "same position, which would cut the mesh "
                         "apart there): pairs of ids "
                       + first_few(bad));

    // deal.II 9.4 cannot put one finite element on cells of several kinds
    // (it would crash distributing the degrees of freedom).
    std::vector<unsigned int> other_kind;
    const auto first = triangulation.begin_active()->reference_cell();
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->reference_cell() != first)
        other_kind.push_back(cell->active_cell_index());
    if (!other_kind.empty())
      throw InputError(where + "mixes cell types ("
                       + std::to_string(other_kind.size()) + " cells are not "
                       + first.to_string()
                       + " like cell 0), which tissuefem cannot mesh with one "
                         "element: ids "
                       + first_few(other_kind));

    std::vector<unsigned int> degenerate, inverted;
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        double length = 0;
        for (unsigned int v = 1; v < cell->n_vertices(); ++v)
          length = std::max(length, cell->vertex(v).distance(cell->vertex(0)));
        const double det = smallest_vertex_jacobian<dim>(cell);
        if (std::abs(det) <= 1e-12 * std::pow(length, dim))
          degenerate.push_back(cell->active_cell_index());
        else if (det < 0)
          inverted.push_back(cell->active_cell_index());
      }
    if (!degenerate.empty())
      throw InputError(where + std::to_string(degenerate.size())
                       + " degenerate cells (zero volume): ids "
                       + first_few(degenerate));
    if (!inverted.empty())
      throw InputError(where + std::to_string(inverted.size())
                       + " inverted cells (negative volume: vertices in the "
                         "wrong order): ids "
                       + first_few(inverted));
  }


  GmshSurvey
  survey_gmsh(const std::string &file, const int dim)
  {
    std::ifstream                         in(file);
    std::map<long, std::array<double, 3>> nodes;
    std::string                           line;
    GmshSurvey                            survey;
    std::map<long, unsigned int>          uses; // element number -> count
    // Gmsh 1.0 ($NOD, $ELM: id type phys elem n nodes...) and 2.x ASCII
    // ($Nodes, $Elements: id type n_tags tags... nodes...).
    enum
    {
      none,
      node_list,
      element_list
    } section
      = none;
    bool version2 = false, counted = false;
    while (std::getline(in, line))
      {
        // Gmsh 4 lists nodes and elements in blocks: not counted here.
        if (line.rfind("$MeshFormat", 0) == 0 && std::getline(in, line)
            && line.rfind("4", 0) == 0)
          return {};
        if (line.rfind("$NOD", 0) == 0 || line.rfind("$Nodes", 0) == 0)
          {
            section  = node_list;
            version2 = line.rfind("$Nodes", 0) == 0;
            counted  = false;
            continue;
          }
        if (line.rfind("$ELM", 0) == 0 || line.rfind("$Elements", 0) == 0)
          {
            section = element_list;
            counted = false;
            continue;
          }
        if (line.rfind("$", 0) == 0)
          {
            section = none;
            continue;
          }
        std::istringstream fields(line);
        if (section == none)
          continue;
        if (!counted)
          {
            counted = true; // the count line
            continue;
          }
        if (section == node_list)
          {
            long                  id;
            std::array<double, 3> x{};
            if (fields >> id >> x[0] >> x[1] >> x[2])
              nodes[id] = x;
            continue;
          }
        long id, type, n_nodes = 0;
        if (!(fields >> id >> type))
          return {};
        if (++uses[id] == 2)
          survey.repeated_numbers.push_back(id);
        if (version2)
          {
            long n_tags, tag;
            fields >> n_tags;
            for (long t = 0; t < n_tags; ++t)
              fields >> tag;
            n_nodes = type == 2 ? 3 : type == 4 ? 4 : 0;
          }
        else
          {
            long physical, elementary;
            fields >> physical >> elementary >> n_nodes;
          }
        if (!((dim == 2 && type == 2 && n_nodes == 3)
              || (dim == 3 && type == 4 && n_nodes == 4)))
          continue;
        std::array<std::array<double, 3>, 4> x;
        std::array<long, 4>                  listed{};
        for (long k = 0; k < n_nodes; ++k)
          {
            long node;
            if (!(fields >> node) || nodes.count(node) == 0)
              return {}; // the reader reports it
            x[k]      = nodes[node];
            listed[k] = node;
          }
        std::sort(listed.begin(), listed.begin() + n_nodes);
        if (std::adjacent_find(listed.begin(), listed.begin() + n_nodes)
            != listed.begin() + n_nodes)
          survey.repeated_node_elements.push_back(id);
        double e[3][3];
        for (int k = 0; k < dim; ++k)
          for (int c = 0; c < 3; ++c)
            e[k][c] = x[k + 1][c] - x[0][c];
        const double volume
          = dim == 2 ? e[0][0] * e[1][1] - e[0][1] * e[1][0]
                     : e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1])
                         - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0])
                         + e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
        if (volume < 0)
          ++survey.inverted;
      }
    for (const long number : survey.repeated_numbers)
      survey.repeated_uses.push_back(uses[number]);
    return survey;
  }


  template void
  check_mesh<1>(const Triangulation<1> &, const std::string &);
  template void
  check_mesh<2>(const Triangulation<2> &, const std::string &);
  template void
  check_mesh<3>(const Triangulation<3> &, const std::string &);
} // namespace tissuefem::geometry
