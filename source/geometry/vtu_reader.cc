#include <deal.II/base/geometry_info.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/geometry/vtu_reader.h>

#include <algorithm>
#include <cctype>
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

    /// An element found by the text scan: its start tag's attributes (white
    /// space made blanks) and where its content and its end tag end.
    struct Element
    {
      std::string attributes;
      std::size_t content_begin = npos, content_end = npos, end = npos;

      bool
      found() const
      {
        return content_begin != npos;
      }

      /// The value of attribute @p name, "" if there is none. Writers put
      /// no blanks around '=', so we do not look for any.
      std::string
      attribute(const std::string &name) const
      {
        for (const char quote : {'"', '\''})
          if (const std::size_t pos = attributes.find(' ' + name + '=' + quote);
              pos != npos)
            {
              const std::size_t begin = pos + name.size() + 3;
              return attributes.substr(begin,
                                       attributes.find(quote, begin) - begin);
            }
        return "";
      }
    };

    // The files we read are machine-written and simply nested, so finding
    // tags by string search suffices and spares an XML library.
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
        std::size_t pos = text.find('<' + name, from);
        while (pos < std::min(to, text.size()))
          {
            const std::size_t after = pos + 1 + name.size();
            const char        next  = after < text.size() ? text[after] : '<';
            if (std::isspace(next) || next == '>' || next == '/')
              {
                const std::size_t close = text.find('>', after);
                if (close == npos)
                  fail("the <" + name + "> tag is not terminated");
                const bool self_closing = text[close - 1] == '/';
                Element    element;
                element.attributes
                  = ' ' + text.substr(after, close - after - self_closing);
                for (char &c : element.attributes)
                  c = std::isspace(c) ? ' ' : c;
                element.content_begin = close + 1;
                element.content_end
                  = self_closing ? close + 1 : text.find("</" + name, close);
                element.end = text.find('>', element.content_end);
                if (element.content_end == npos || element.end == npos)
                  fail("<" + name + "> is not closed");
                ++element.end;
                return element;
              }
            pos = text.find('<' + name, after);
          }
        return Element();
      }

      Element
      find_array(const Element &section, const std::string &name) const
      {
        Element array
          = find("DataArray", section.content_begin, section.content_end);
        while (array.found() && array.attribute("Name") != name)
          array = find("DataArray", array.end, section.content_end);
        return array;
      }

      /// The numbers of an ASCII DataArray; @p expected of them unless npos.
      std::vector<double>
      numbers(const Element     &array,
              const std::string &name,
              const std::size_t  expected,
              const bool         integer) const
      {
        const std::string format = array.attribute("format");
        if (!format.empty() && format != "ascii")
          fail("DataArray '" + name + "' has format=\"" + format
               + "\"; only ascii data can be read");
        std::vector<double> result;
        std::istringstream  in(
          text.substr(array.content_begin,
                      array.content_end - array.content_begin));
        std::string token;
        while (in >> token)
          {
            char        *stop  = nullptr;
            const double value = std::strtod(token.c_str(), &stop);
            if (*stop != '\0' || !std::isfinite(value)
                || (integer
                    && (value != std::floor(value) || std::abs(value) > 1e15)))
              fail("DataArray '" + name + "' holds '" + token.substr(0, 20)
                   + "', which is not "
                   + (integer ? "an integer" : "a number"));
            result.push_back(value);
          }
        if (expected != npos && result.size() != expected)
          fail("DataArray '" + name + "' holds " + std::to_string(result.size())
               + " values, but " + std::to_string(expected) + " are expected");
        return result;
      }

      std::size_t
      count(const Element &piece, const std::string &name) const
      {
        const std::string value = piece.attribute(name);
        char             *stop  = nullptr;
        const long long   n     = std::strtoll(value.c_str(), &stop, 10);
        if (value.empty() || *stop != '\0' || n < 0)
          fail("<Piece> has no valid " + name + " attribute");
        return n;
      }
    };

    // The dimension of VTK cell types 0..25 ('-': unknown), after VTK's
    // vtkCellType.h, so that lower-dimensional cells can be skipped.
    constexpr char vtk_dimensions[] = "-00112222233333------12233";

    std::string
    str(const double integer)
    {
      return std::to_string(static_cast<long long>(integer));
    }

    // VTK numbers quadrilateral and hexahedron vertices counterclockwise,
    // deal.II lexicographically; simplices number alike.
    std::vector<unsigned int>
    to_deal_ii_order(const std::vector<unsigned int> &vtk, const bool cube)
    {
      static const unsigned int order[] = {0, 1, 3, 2, 4, 5, 7, 6};
      std::vector<unsigned int> result(vtk);
      for (unsigned int i = 0; cube && i < vtk.size(); ++i)
        result[i] = vtk[order[i]];
      return result;
    }

    /// The sorted vertices of each face of a (deal.II-ordered) cell: the
    /// key under which a face listed separately in the file is found.
    template <int dim>
    std::vector<std::vector<unsigned int>>
    face_keys(const std::vector<unsigned int> &v, const bool cube)
    {
      std::vector<std::vector<unsigned int>> keys;
      for (unsigned int f = 0; f < (cube ? 2 * dim : dim + 1); ++f)
        {
          std::vector<unsigned int> key;
          for (unsigned int i = 0; cube && i < (1u << (dim - 1)); ++i)
            key.push_back(v[GeometryInfo<dim>::face_to_cell_vertices(f, i)]);
          if (!cube)
            {
              key = v;
              key.erase(key.begin() + f);
            }
          std::sort(key.begin(), key.end());
          keys.push_back(key);
        }
      return keys;
    }

    /// The arrays of the file's one <Piece>, as numbers: coordinates (x, y,
    /// z per point), the cells' connectivity, offsets and VTK types, and
    /// their ids (empty if the file has none).
    struct PieceData
    {
      std::size_t         n_points = 0, n_cells = 0;
      std::vector<double> xyz, connectivity, offsets, cell_types, ids;
    };

    /// Checks the file's structure and reads the arrays of its piece.
    PieceData
    read_piece(const Scanner &s)
    {
      if (s.find("VTKFile", 0, npos).attribute("type") != "UnstructuredGrid")
        s.fail("is no VTK XML UnstructuredGrid file");
      if (s.find("AppendedData", 0, npos).found())
        s.fail("holds appended data; only ascii data can be read");
      const Element piece = s.find("Piece", 0, npos);
      if (!piece.found() || s.find("Piece", piece.end, npos).found())
        s.fail("must hold exactly one <Piece>");
      PieceData data;
      data.n_points      = s.count(piece, "NumberOfPoints");
      data.n_cells       = s.count(piece, "NumberOfCells");
      const auto section = [&](const std::string &name) {
        return s.find(name, piece.content_begin, piece.content_end);
      };

      const Element points = section("Points");
      const Element coordinates
        = s.find("DataArray", points.content_begin, points.content_end);
      if (!points.found() || !coordinates.found()
          || coordinates.attribute("NumberOfComponents") != "3")
        s.fail("has no <Points> DataArray with NumberOfComponents=\"3\"");
      data.xyz = s.numbers(coordinates, "Points", 3 * data.n_points, false);

      std::vector<double> *arrays[3]
        = {&data.connectivity, &data.offsets, &data.cell_types};
      const char   *names[3]      = {"connectivity", "offsets", "types"};
      const Element cells_section = section("Cells");
      for (unsigned int i = 0; i < 3; ++i)
        {
          const Element array = s.find_array(cells_section, names[i]);
          if (!cells_section.found() || !array.found())
            s.fail(std::string("has no <Cells> DataArray Name=\"") + names[i]
                   + "\"");
          *arrays[i]
            = s.numbers(array, names[i], i ? data.n_cells : npos, true);
        }

      const Element cell_data = section("CellData");
      for (const std::string name :
           {"MaterialIds", "material_id", "materialID", "gmsh:physical"})
        if (const Element array = s.find_array(cell_data, name);
            cell_data.found() && array.found())
          {
            if (array.attribute("type").find("Int") == npos)
              s.fail("CellData array '" + name + "' must have an integer type");
            data.ids = s.numbers(array, name, data.n_cells, true);
            break;
          }
      return data;
    }

    /// The id of cell @p c (material or boundary id; 0 without ids).
    unsigned int
    cell_id(const Scanner &s, const PieceData &data, const std::size_t c)
    {
      const std::vector<double> &ids = data.ids;
      if (!ids.empty() && (ids[c] < 0 || ids[c] > 254))
        s.fail("cell " + std::to_string(c) + " has id " + str(ids[c])
               + ", but ids must be 0..254");
      return ids.empty() ? 0u : static_cast<unsigned int>(ids[c]);
    }

    /// The vertices in @p dim coordinates. A 2D mesh comes with z; it must
    /// not hide a curved surface.
    template <int dim>
    std::vector<Point<dim>>
    read_vertices(const Scanner &s, const PieceData &data)
    {
      const std::vector<double> &xyz = data.xyz;
      std::vector<Point<dim>>    vertices(data.n_points);
      double                     extent = 0;
      for (std::size_t i = 0; i < data.n_points; ++i)
        for (unsigned int d = 0; d < dim; ++d)
          {
            vertices[i][d] = xyz[3 * i + d];
            extent = std::max(extent, std::abs(xyz[3 * i + d] - xyz[d]));
          }
      for (std::size_t i = 0; dim == 2 && i < data.n_points; ++i)
        if (std::abs(xyz[3 * i + 2] - xyz[2]) > 1e-10 * extent)
          s.fail("point " + std::to_string(i) + " has another z than point 0, "
                 + "but a 2D mesh must lie in a plane z = const");
      return vertices;
    }

    /// The point indices of cell @p c in VTK's order, checked against the
    /// offsets and the number of points.
    std::vector<unsigned int>
    vtk_cell_vertices(const Scanner &s, const PieceData &data, std::size_t c)
    {
      const std::vector<double> &connectivity = data.connectivity;
      const std::vector<double> &offsets      = data.offsets;
      const double               begin        = c == 0 ? 0 : offsets[c - 1];
      if (offsets[c] < begin || offsets[c] > connectivity.size()
          || (c + 1 == data.n_cells && offsets[c] != connectivity.size()))
        s.fail("offset " + str(offsets[c]) + " of cell " + std::to_string(c)
               + " does not fit " + std::to_string(connectivity.size())
               + " connectivity entries");
      std::vector<unsigned int> vtk;
      for (std::size_t k = begin; k < offsets[c]; ++k)
        {
          if (connectivity[k] < 0 || connectivity[k] >= data.n_points)
            s.fail("cell " + std::to_string(c) + " refers to point "
                   + str(connectivity[k]) + ", but the file has "
                   + std::to_string(data.n_points) + " points");
          vtk.push_back(connectivity[k]);
        }
      return vtk;
    }

    /// The cells of the mesh's dimension, and the faces tagged with ids
    /// (with the index of the file's cell each came from).
    template <int dim>
    struct CellLists
    {
      std::vector<CellData<dim>>                             cells;
      std::vector<std::pair<std::size_t, CellData<dim - 1>>> faces;
      unsigned int                                           n_cubes = 0;
    };

    /// Sorts the file's cells into cells and tagged faces; lower-
    /// dimensional cells without ids are skipped.
    template <int dim>
    CellLists<dim>
    read_cells(const Scanner &s, const PieceData &data)
    {
      CellLists<dim> lists;
      for (std::size_t c = 0; c < data.n_cells; ++c)
        {
          const std::vector<unsigned int> vtk  = vtk_cell_vertices(s, data, c);
          const int                       type = data.cell_types[c];
          const int                       cell_dim
            = type >= 0 && type <= 25 ? vtk_dimensions[type] - '0' : -1;
          const std::string what
            = "cell " + std::to_string(c) + " (VTK type " + str(type) + ")";
          if (cell_dim < 0 || cell_dim > dim)
            s.fail(what + " cannot be read into a " + std::to_string(dim)
                   + "D mesh");
          const bool cube = type == 9 || type == 12;
          const bool used = cell_dim == dim
                            || (!data.ids.empty() && cell_dim == dim - 1
                                && (dim == 2 ? type == 3 : type == 5 || cube));
          if (cell_dim == dim && type != (dim == 3 ? 10 : 5)
              && type != (dim == 3 ? 12 : 9))
            s.fail(what + " is not supported; use "
                   + (dim == 3 ? "tetrahedra or hexahedra"
                               : "triangles or quadrilaterals"));
          const std::size_t n_vertices = type == 3 ? 2 : type == 5 ? 3 : 4;
          if (used && vtk.size() != (type == 12 ? 8 : n_vertices))
            s.fail(what + " has " + std::to_string(vtk.size()) + " points");
          if (cell_dim == dim)
            {
              lists.cells.emplace_back(vtk.size());
              lists.cells.back().vertices    = to_deal_ii_order(vtk, cube);
              lists.cells.back().material_id = cell_id(s, data, c);
              lists.n_cubes += cube;
            }
          else if (used)
            {
              lists.faces.emplace_back(c, CellData<dim - 1>(vtk.size()));
              lists.faces.back().second.vertices = to_deal_ii_order(vtk, cube);
              lists.faces.back().second.boundary_id = cell_id(s, data, c);
            }
        }
      if (lists.cells.empty())
        s.fail("holds no " + std::to_string(dim) + "D cells");
      if (lists.n_cubes != 0 && lists.n_cubes != lists.cells.size())
        s.fail("mixes simplices and hypercubes, which deal.II cannot join "
               "without wedges or pyramids");
      return lists;
    }

    /// deal.II needs positive Jacobians, which meshing tools do not always
    /// produce; swapping two vertices turns a simplex inside out.
    /// Hypercubes are left to deal.II's own repair.
    template <int dim>
    void
    reorient_simplices(const Scanner                 &s,
                       const std::vector<Point<dim>> &vertices,
                       CellLists<dim>                &lists)
    {
      unsigned int n_reoriented = 0;
      for (std::size_t c = 0; c < lists.cells.size() && lists.n_cubes == 0; ++c)
        {
          std::vector<unsigned int> &v = lists.cells[c].vertices;
          Tensor<2, dim>             edges;
          double                     length = 0;
          for (unsigned int d = 0; d < dim; ++d)
            {
              edges[d] = vertices[v[d + 1]] - vertices[v[0]];
              length   = std::max(length, edges[d].norm());
            }
          const double measure = determinant(edges);
          if (std::abs(measure) <= 1e-12 * std::pow(length, dim))
            s.fail("cell " + std::to_string(c)
                   + " is degenerate (zero volume)");
          if (measure < 0)
            {
              std::swap(v[1], v[2]);
              ++n_reoriented;
            }
        }
      if (n_reoriented > 0)
        parallel_tools::screen()
          << "Mesh file '" << s.file_name << "': " << n_reoriented
          << " cells had their vertices in inverted order and were "
             "reoriented (a safe repair: the cell is the same)."
          << std::endl;
    }

    /// The tagged faces that lie on the boundary. deal.II's ids belong to
    /// boundary faces; a file may also tag faces between cells (e.g.
    /// material interfaces), which it cannot hold: those are dropped.
    template <int dim>
    SubCellData
    boundary_faces(const Scanner &s, const CellLists<dim> &lists)
    {
      std::map<std::vector<unsigned int>, unsigned int> n_adjacent;
      for (std::size_t c = 0; c < lists.cells.size() && !lists.faces.empty();
           ++c)
        for (const auto &key :
             face_keys<dim>(lists.cells[c].vertices, lists.n_cubes))
          ++n_adjacent[key];
      SubCellData subcell_data;
      for (const auto &[c, face] : lists.faces)
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
      return subcell_data;
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

      const PieceData         data     = read_piece(s);
      std::vector<Point<dim>> vertices = read_vertices<dim>(s, data);
      CellLists<dim>          lists    = read_cells<dim>(s, data);
      reorient_simplices(s, vertices, lists);
      SubCellData subcell_data = boundary_faces(s, lists);

      GridTools::delete_unused_vertices(vertices, lists.cells, subcell_data);
      try
        {
          if (lists.n_cubes != 0)
            {
              GridTools::invert_all_negative_measure_cells(vertices,
                                                           lists.cells);
              GridTools::consistently_order_cells(lists.cells);
            }
          tria.create_triangulation(vertices, lists.cells, subcell_data);
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
