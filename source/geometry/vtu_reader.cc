#include <deal.II/base/geometry_info.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/geometry/vtu_reader.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace tissuefem::geometry
{
  namespace
  {
    constexpr std::size_t npos = std::string::npos;

    /// An element found by the text scan: its start tag's attribute text
    /// and the range of its content.
    struct Element
    {
      std::string attributes;
      std::size_t content_begin = npos, content_end = npos, end = npos;

      bool
      found() const
      {
        return content_begin != npos;
      }
    };

    /// The value of attribute @p name, "" if the element has none.
    std::string
    attribute(const Element &element, const std::string &name)
    {
      const std::string &a = element.attributes;
      for (std::size_t pos = a.find(name); pos != npos;
           pos             = a.find(name, pos + 1))
        {
                      std::size_t p = pos + name.size();
                      while (p < a.size() && std::isspace(a[p]))
            ++p;
          if ((pos > 0 && !std::isspace(a[pos - 1])) || p >= a.size()
              || a[p] != '=')
            continue;
          ++p;
                      while (p < a.size() && std::isspace(a[p]))
            ++p;
          if (p < a.size() && (a[p] == '"' || a[p] == '\''))
            {
                          const std::size_t close = a.find(a[p], p + 1);
                          if (close != npos)
                return a.substr(p + 1, close - p - 1);
            }
        }
      return "";
    }

    // The files we need to read are machine-written and simply nested, so
    // finding tags by string search is enough and spares an XML library.
    struct Scanner
    {
      std::string file_name;
      std::string text;

      [[noreturn]] void
      fail(const std::string &what) const
      {
        throw InputError("Mesh file '" + file_name + "': " + what);
      }

      /// The first element <name ...> that starts in [from, to).
      Element
      find(const std::string &name, std::size_t from, std::size_t to) const
      {
        to = std::min(to, text.size());
        for (std::size_t pos = text.find('<' + name, from); pos < to;
             pos             = text.find('<' + name, pos + 1))
          {
                        const std::size_t after = pos + 1 + name.size();
                        if (after >= text.size()
                || !(std::isspace(text[after]) || text[after] == '>'
                     || text[after] == '/'))
              continue;
            const std::size_t close = text.find('>', after);
                        if (close == npos)
              fail("the <" + name + "> tag is not terminated");
            const bool self_closing = text[close - 1] == '/';
                        Element    element;
                        element.attributes
                          = text.substr(after, close - after - (self_closing ? 1 : 0));
                        element.content_begin = close + 1;
                        element.content_end
                          = self_closing ? close + 1 : text.find("</" + name, close);
                        if (element.content_end == npos)
              fail("<" + name + "> is not closed");
            element.end = text.find('>', element.content_end);
                        if (element.end == npos)
              fail("</" + name + "> is not terminated");
            ++element.end;
                        return element;
          }
        return Element();
      }

      Element
      find_array(const Element &section, const std::string &name) const
      {
        for (Element array
             = find("DataArray", section.content_begin, section.content_end);
             array.found();
             array = find("DataArray", array.end, section.content_end))
          if (attribute(array, "Name") == name)
            return array;
        return Element();
      }

      /// Parses the whitespace-separated numbers of an ASCII DataArray with
      /// @p parse, expecting @p expected of them (npos: any number).
      template <typename T, typename Parse>
      std::vector<T>
      values(const Element     &array,
             const std::string &name,
             const std::size_t  expected,
             const Parse       &parse) const
      {
        const std::string format = attribute(array, "format");
        if (!format.empty() && format != "ascii")
          fail("DataArray '" + name + "' has format=\"" + format
               + "\"; only ascii data can be read (save the mesh with ASCII "
                 "data)");
        std::vector<T> result;
        const char    *p   = text.c_str() + array.content_begin;
        const char    *end = text.c_str() + array.content_end;
        while (true)
          {
            while (p < end && std::isspace(*p))
              ++p;
            if (p >= end)
              break;
            char *stop    = nullptr;
            errno         = 0;
            const T value = parse(p, &stop);
            if (stop == p || errno == ERANGE
                || (stop < end && !std::isspace(*stop)))
              {
                const char *token_end = p;
                while (token_end < end && !std::isspace(*token_end))
                  ++token_end;
                fail("DataArray '" + name + "' holds '"
                     + std::string(p, std::min<std::size_t>(token_end - p, 20))
                     + "', which is not a valid number of its type");
              }
            result.push_back(value);
            p = stop;
          }
        if (expected != npos && result.size() != expected)
          fail("DataArray '" + name + "' holds " + std::to_string(result.size())
               + " values, but " + std::to_string(expected) + " are expected");
        return result;
      }

      std::vector<double>
      reals(const Element &array, const std::string &name, std::size_t n) const
      {
        return values<double>(array, name, n, [](const char *p, char **stop) {
          return std::strtod(p, stop);
        });
      }

      std::vector<long long>
      integers(const Element     &array,
               const std::string &name,
               std::size_t        n) const
      {
        return values<long long>(array,
                                 name,
                                 n,
                                 [](const char *p, char **stop) {
                                   return std::strtoll(p, stop, 10);
                                 });
      }

      std::size_t
      count(const Element &piece, const std::string &name) const
      {
        const std::string value = attribute(piece, name);
        char             *stop  = nullptr;
        const long long   n     = std::strtoll(value.c_str(), &stop, 10);
        if (value.empty() || *stop != '\0' || n < 0)
          fail("<Piece> has no valid " + name + " attribute");
        return n;
      }
    };

    struct CellKind
    {
      int          dimension;  // -1: a type we do not know
      unsigned int n_vertices; // 0: any number
      const char  *name;
    };

    CellKind
    cell_kind(const long long type)
    {
      switch (type)
        {
          case 1:
            return {0, 1, "vertex"};
          case 2:
            return {0, 0, "poly-vertex"};
          case 3:
            return {1, 2, "line"};
          case 4:
            return {1, 0, "poly-line"};
          case 5:
            return {2, 3, "triangle"};
          case 6:
            return {2, 0, "triangle strip"};
          case 7:
            return {2, 0, "polygon"};
          case 8:
            return {2, 4, "pixel"};
          case 9:
            return {2, 4, "quadrilateral"};
          case 10:
            return {3, 4, "tetrahedron"};
          case 11:
            return {3, 8, "voxel"};
          case 12:
            return {3, 8, "hexahedron"};
          case 13:
            return {3, 6, "wedge"};
          case 14:
            return {3, 5, "pyramid"};
          case 21:
            return {1, 3, "quadratic line"};
          case 22:
            return {2, 6, "quadratic triangle"};
          case 23:
            return {2, 8, "quadratic quadrilateral"};
          case 24:
            return {3, 10, "quadratic tetrahedron"};
          case 25:
            return {3, 20, "quadratic hexahedron"};
          default:
            return {-1, 0, "unknown"};
        }
    }

    // VTK numbers quadrilateral and hexahedron vertices counterclockwise,
    // deal.II lexicographically; simplices number alike.
    std::vector<unsigned int>
    to_deal_ii_order(const std::vector<unsigned int> &vtk, const bool cube)
    {
      static const unsigned int quad[] = {0, 1, 3, 2};
      static const unsigned int hex[]  = {0, 1, 3, 2, 4, 5, 7, 6};
      if (!cube)
        return vtk;
      std::vector<unsigned int> result(vtk.size());
      for (unsigned int i = 0; i < vtk.size(); ++i)
        result[i] = vtk[vtk.size() == 4 ? quad[i] : hex[i]];
      return result;
    }

    /// The signed measure of a simplex, and its largest edge from vertex 0
    /// to the power dim (the scale that tells a degenerate one).
    template <int dim>
    std::pair<double, double>
    simplex_measure(const std::vector<Point<dim>>   &points,
                    const std::vector<unsigned int> &v)
    {
      Tensor<1, dim> e[dim];
      double         length = 0;
      for (unsigned int d = 0; d < dim; ++d)
        {
          e[d]   = points[v[d + 1]] - points[v[0]];
          length = std::max(length, e[d].norm());
        }
      if constexpr (dim == 2)
        return {e[0][0] * e[1][1] - e[0][1] * e[1][0], length * length};
      else
        return {scalar_product(e[0], cross_product_3d(e[1], e[2])),
                length * length * length};
    }

    template <int dim>
    void
    read_vtu_mesh(const std::string &file_name, Triangulation<dim> &tria)
    {
      std::ifstream in(file_name, std::ios::binary);
      if (!in)
        throw InputError("Mesh file '" + file_name + "' cannot be opened");
      std::ostringstream buffer;
      buffer << in.rdbuf();
      const Scanner s{file_name, buffer.str()};

      const Element file = s.find("VTKFile", 0, npos);
      if (!file.found() || attribute(file, "type") != "UnstructuredGrid")
        s.fail("is no VTK XML UnstructuredGrid file");
      if (s.find("AppendedData", 0, npos).found())
        s.fail("holds appended data; only ascii data can be read (save the "
               "mesh with ASCII data)");
      const Element piece = s.find("Piece", 0, npos);
      if (!piece.found())
        s.fail("has no <Piece>");
      if (s.find("Piece", piece.end, npos).found())
        s.fail("has several <Piece> elements; only one can be read");
      const std::size_t n_points = s.count(piece, "NumberOfPoints");
      const std::size_t n_cells  = s.count(piece, "NumberOfCells");

      const Element points
        = s.find("Points", piece.content_begin, piece.content_end);
      const Element coordinates
        = s.find("DataArray", points.content_begin, points.content_end);
      if (!points.found() || !coordinates.found())
        s.fail("has no <Points> DataArray");
      if (attribute(coordinates, "NumberOfComponents") != "3")
        s.fail("the <Points> DataArray must have NumberOfComponents=\"3\"");
      const std::vector<double> xyz
        = s.reals(coordinates, "Points", 3 * n_points);

      const Element cells_section
        = s.find("Cells", piece.content_begin, piece.content_end);
      std::vector<long long> arrays[3];
      const char            *names[3] = {"connectivity", "offsets", "types"};
      for (unsigned int i = 0; i < 3; ++i)
        {
          const Element array = s.find_array(cells_section, names[i]);
          if (!cells_section.found() || !array.found())
            s.fail(std::string("has no <Cells> DataArray Name=\"") + names[i]
                   + "\"");
          arrays[i] = s.integers(array, names[i], i == 0 ? npos : n_cells);
        }
      const auto &[connectivity, offsets, cell_types] = arrays;

      std::vector<long long> ids;
      const Element          cell_data
        = s.find("CellData", piece.content_begin, piece.content_end);
      if (cell_data.found())
        for (const std::string name :
             {"MaterialIds", "material_id", "materialID", "gmsh:physical"})
          if (const Element array = s.find_array(cell_data, name);
              array.found())
            {
              const std::string type = attribute(array, "type");
              if (type.rfind("Int", 0) != 0 && type.rfind("UInt", 0) != 0)
                s.fail("CellData array '" + name + "' has type '" + type
                       + "', but ids need an integer type");
              ids = s.integers(array, name, n_cells);
              break;
            }

      std::vector<Point<dim>> vertices(n_points);
      double                  extent = 0;
      for (std::size_t i = 0; i < n_points; ++i)
        for (unsigned int d = 0; d < dim; ++d)
          {
            if (!std::isfinite(xyz[3 * i + d]))
              s.fail("point " + std::to_string(i)
                     + " has a non-finite "
                       "coordinate");
            vertices[i][d] = xyz[3 * i + d];
            extent = std::max(extent, std::abs(xyz[3 * i + d] - xyz[d]));
          }
      for (std::size_t i = 0; dim == 2 && i < n_points; ++i)
        if (std::abs(xyz[3 * i + 2] - xyz[2]) > 1e-10 * extent)
          s.fail("point " + std::to_string(i)
                 + " has another z than point 0, "
                   "but a 2D mesh must lie in a plane z = constant");

      const auto checked_id = [&](const std::size_t c) {
        if (ids.empty())
          return 0u;
        if (ids[c] < 0 || ids[c] > 254)
          s.fail("cell " + std::to_string(c) + " has id "
                 + std::to_string(ids[c]) + "; ids must be 0..254");
        return static_cast<unsigned int>(ids[c]);
      };

      std::vector<CellData<dim>>                             cells;
      SubCellData                                            subcell_data;
      std::vector<std::pair<std::size_t, CellData<dim - 1>>> faces;
      unsigned int                                           n_cubes = 0;
      for (std::size_t c = 0; c < n_cells; ++c)
        {
          const long long begin = c == 0 ? 0 : offsets[c - 1];
          if (offsets[c] < begin
              || offsets[c] > static_cast<long long>(connectivity.size()))
            s.fail("offset " + std::to_string(offsets[c]) + " of cell "
                   + std::to_string(c) + " is decreasing or beyond the "
                   + std::to_string(connectivity.size())
                   + " connectivity entries");
          std::vector<unsigned int> vtk;
          for (long long k = begin; k < offsets[c]; ++k)
            {
              if (connectivity[k] < 0
                  || connectivity[k] >= static_cast<long long>(n_points))
                s.fail("cell " + std::to_string(c) + " refers to point "
                       + std::to_string(connectivity[k]) + ", but the file has "
                       + std::to_string(n_points) + " points");
              vtk.push_back(connectivity[k]);
            }

          const CellKind    kind = cell_kind(cell_types[c]);
          const std::string what = "cell " + std::to_string(c) + " (VTK type "
                                   + std::to_string(cell_types[c]) + ", "
                                   + kind.name + ")";
          if (kind.dimension < 0 || kind.dimension > dim)
            s.fail(what + " cannot be read into a " + std::to_string(dim)
                   + "D mesh");
          if (kind.n_vertices != 0 && vtk.size() != kind.n_vertices)
            s.fail(what + " has " + std::to_string(vtk.size()) + " points");
          const bool simplex = cell_types[c] == 5 || cell_types[c] == 10;
          const bool cube    = cell_types[c] == 9 || cell_types[c] == 12;
          const bool usable  = (cell_types[c] == (dim == 3 ? 10 : 5))
                              || (cell_types[c] == (dim == 3 ? 12 : 9));
          if (kind.dimension == dim)
            {
              if (!usable)
                s.fail(what + " is not supported; use "
                       + (dim == 3 ? "tetrahedra or hexahedra"
                                   : "triangles or quadrilaterals"));
              cells.emplace_back(vtk.size());
              cells.back().vertices    = to_deal_ii_order(vtk, cube);
              cells.back().material_id = checked_id(c);
              n_cubes += cube;
            }
          else if (kind.dimension == dim - 1 && !ids.empty()
                   && (dim == 2 ? cell_types[c] == 3 : simplex || cube))
            {
              faces.emplace_back(c, CellData<dim - 1>(vtk.size()));
              faces.back().second.vertices    = to_deal_ii_order(vtk, cube);
              faces.back().second.boundary_id = checked_id(c);
            }
        }
      if (n_cells > 0
          && offsets.back() != static_cast<long long>(connectivity.size()))
        s.fail("the last offset is " + std::to_string(offsets.back())
               + ", but there are " + std::to_string(connectivity.size())
               + " connectivity entries");
      if (cells.empty())
        s.fail("holds no " + std::to_string(dim) + "D cells");
      if (n_cubes != 0 && n_cubes != cells.size())
        s.fail("mixes simplices and hypercubes, which deal.II cannot join "
               "without wedges or pyramids");

      // deal.II needs positive Jacobians; meshing tools often do not care
      // about orientation, and a swap of two vertices fixes a simplex.
      for (std::size_t c = 0; c < cells.size() && n_cubes == 0; ++c)
        {
          auto &v                     = cells[c].vertices;
          const auto [measure, scale] = simplex_measure(vertices, v);
          if (std::abs(measure) <= 1e-12 * scale)
            s.fail("cell " + std::to_string(c)
                   + " is degenerate (zero volume)");
          if (measure < 0)
            std::swap(v[1], v[2]);
        }
      try
        {
          if (n_cubes != 0)
            {
              GridTools::invert_all_negative_measure_cells(vertices, cells);
              GridTools::consistently_order_cells(cells);
            }
        }
      catch (const ExceptionBase &e)
        {
          s.fail("its cells cannot be oriented consistently: "
                 + one_line_message(e));
        }

      // deal.II's ids belong to boundary faces only; a file may also tag
      // interfaces inside the mesh, which we cannot represent.
      if (!faces.empty())
        {
          std::map<std::vector<unsigned int>, unsigned int> n_adjacent;
          for (const auto &cell : cells)
            for (unsigned int f = 0; f < 2 * dim && n_cubes != 0; ++f)
              {
                std::vector<unsigned int> key;
                for (unsigned int i = 0;
                     i < GeometryInfo<dim>::vertices_per_face;
                     ++i)
                  key.push_back(
                    cell.vertices[GeometryInfo<dim>::face_to_cell_vertices(f,
                                                                           i)]);
                std::sort(key.begin(), key.end());
                ++n_adjacent[key];
              }
          for (const auto &cell : cells)
            for (unsigned int f = 0; f <= dim && n_cubes == 0; ++f)
              {
                std::vector<unsigned int> key = cell.vertices;
                key.erase(key.begin() + f);
                std::sort(key.begin(), key.end());
                ++n_adjacent[key];
              }
          for (const auto &[c, face] : faces)
            {
              std::vector<unsigned int> key = face.vertices;
              std::sort(key.begin(), key.end());
              const auto adjacent = n_adjacent.find(key);
              if (adjacent == n_adjacent.end())
                s.fail("cell " + std::to_string(c) + " is no face of any "
                       + std::to_string(dim) + "D cell");
              if (adjacent->second != 1)
                continue;
              if constexpr (dim == 2)
                subcell_data.boundary_lines.push_back(face);
              else
                subcell_data.boundary_quads.push_back(face);
            }
        }

      GridTools::delete_unused_vertices(vertices, cells, subcell_data);
      try
        {
          tria.create_triangulation(vertices, cells, subcell_data);
        }
      catch (const ExceptionBase &e)
        {
          s.fail("deal.II cannot build a mesh from it: " + one_line_message(e));
        }
    }
  } // namespace


  template <int dim>
  void
  read_vtu(const std::string &file_name, Triangulation<dim> &triangulation)
  {
    if constexpr (dim == 1)
      {
        (void)triangulation;
        throw InputError("Mesh file '" + file_name
                         + "': .vtu meshes need Dimension 2 or 3");
      }
    else
      read_vtu_mesh(file_name, triangulation);
  }

  template void
  read_vtu<1>(const std::string &, Triangulation<1> &);
  template void
  read_vtu<2>(const std::string &, Triangulation<2> &);
  template void
  read_vtu<3>(const std::string &, Triangulation<3> &);
} // namespace tissuefem::geometry
