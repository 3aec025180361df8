#include <deal.II/base/symmetric_tensor.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/contact/triangle_surface.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>

namespace tissuefem::contact
{
  namespace
  {
    using Triangles = std::vector<std::array<unsigned int, 3>>;

    /// Vertices merged where their coordinates are equal (STL repeats
    /// them for every triangle).
    struct VertexList
    {
      std::vector<Point<3>>                         points;
      std::map<std::array<double, 3>, unsigned int> index;

      unsigned int
      add(const double x, const double y, const double z)
      {
        const auto [it, added]
          = index.emplace(std::array<double, 3>{{x, y, z}}, points.size());
        if (added)
          points.emplace_back(x, y, z);
        return it->second;
      }
    };

    std::string
    describe(const Point<3> &p)
    {
      std::ostringstream text;
      text << '(' << p[0] << ", " << p[1] << ", " << p[2] << ')';
      return text.str();
    }

    /// Binary STL: an 80-byte header, a 4-byte triangle count n, then n
    /// records of 50 bytes (normal, three vertices as 32-bit floats, two
    /// bytes of attributes).
    bool
    read_binary_stl(const std::string &bytes,
                    const double       scale,
                    VertexList        &vertices,
                    Triangles         &triangles)
    {
      if (bytes.size() < 84)
        return false;
      std::uint32_t n = 0;
      std::memcpy(&n, bytes.data() + 80, 4);
      if (bytes.size() != 84 + 50 * std::uint64_t(n))
        return false;
      for (std::uint32_t t = 0; t < n; ++t)
        {
          float values[12];
          std::memcpy(values, bytes.data() + 84 + 50 * std::uint64_t(t), 48);
          std::array<unsigned int, 3> triangle;
          for (unsigned int k = 0; k < 3; ++k)
            triangle[k] = vertices.add(scale * values[3 + 3 * k],
                                       scale * values[4 + 3 * k],
                                       scale * values[5 + 3 * k]);
          triangles.push_back(triangle);
        }
      return true;
    }

    /// ASCII STL: every 'vertex x y z' line, three per facet.
    void
    read_ascii_stl(const std::string &bytes,
                   const std::string &file,
                   const double       scale,
                   VertexList        &vertices,
                   Triangles         &triangles)
    {
      std::istringstream        in(bytes);
      std::string               word;
      std::vector<unsigned int> facet;
      while (in >> word)
        {
          if (word != "vertex")
            continue;
          double x, y, z;
          if (!(in >> x >> y >> z))
            throw InputError("File '" + file
                             + "': a 'vertex' without three numbers");
          facet.push_back(vertices.add(scale * x, scale * y, scale * z));
          if (facet.size() == 3)
            {
              triangles.push_back({{facet[0], facet[1], facet[2]}});
              facet.clear();
            }
        }
      if (!facet.empty())
        throw InputError("File '" + file
                         + "': a facet with fewer than three vertices");
    }

    /// OBJ: 'v x y z' and 'f i j k ...' (indices from 1, negative from the
    /// end, 'i/t/n' forms), polygons split into fans from their first
    /// vertex.
    void
    read_obj(const std::string &bytes,
             const std::string &file,
             const double       scale,
             VertexList        &vertices,
             Triangles         &triangles)
    {
      std::istringstream in(bytes);
      std::string        line;
      // OBJ numbers vertices as written, repeated or not.
      std::vector<unsigned int> numbered;
      for (unsigned int number = 1; std::getline(in, line); ++number)
        {
          std::istringstream words(line);
          std::string        key;
          words >> key;
          const std::string where
            = "File '" + file + "', line " + std::to_string(number) + ": ";
          if (key == "v")
            {
              double x, y, z;
              if (!(words >> x >> y >> z))
                throw InputError(where + "a vertex needs three coordinates");
              numbered.push_back(vertices.add(scale * x, scale * y, scale * z));
            }
          else if (key == "f")
            {
              std::vector<unsigned int> polygon;
              std::string               item;
              while (words >> item)
                {
                  long index = 0;
                  try
                    {
                      index = std::stol(item.substr(0, item.find('/')));
                    }
                  catch (const std::exception &)
                    {
                      throw InputError(where + "'" + item
                                       + "' is not a vertex number");
                    }
                  if (index < 0)
                    index += long(numbered.size()) + 1;
                  if (index < 1 || index > long(numbered.size()))
                    throw InputError(where + "vertex " + item
                                     + " is not defined before this face");
                  polygon.push_back(numbered[index - 1]);
                }
              if (polygon.size() < 3)
                throw InputError(where + "a face needs three vertices");
              for (unsigned int k = 1; k + 1 < polygon.size(); ++k)
                triangles.push_back({{polygon[0], polygon[k], polygon[k + 1]}});
            }
        }
    }
  } // namespace


  TriangleSurface
  TriangleSurface::read(const std::string &file,
                        const std::string &parameter,
                        const double       scale)
  {
    std::ifstream in(file, std::ios::binary);
    require(bool(in), parameter, "cannot open '" + file + "'");
    std::ostringstream buffer;
    buffer << in.rdbuf();
    const std::string bytes = buffer.str();
    require(!bytes.empty(), parameter, "'" + file + "' is empty (0 bytes)");
    std::string extension = std::filesystem::path(file).extension().string();
    for (char &c : extension)
      c = std::tolower(static_cast<unsigned char>(c));
    VertexList vertices;
    Triangles  triangles;
    if (extension == ".stl")
      {
        if (!read_binary_stl(bytes, scale, vertices, triangles))
          {
            // Not a binary file of the size its count gives: ASCII, if it
            // reads as such.
            require(bytes.compare(0, 5, "solid") == 0
                      && bytes.find("facet") != std::string::npos,
                    parameter,
                    "'" + file
                      + "' is neither ASCII STL ('solid' ... 'facet') nor "
                        "binary STL of the size its triangle count gives");
            read_ascii_stl(bytes, file, scale, vertices, triangles);
          }
      }
    else if (extension == ".obj")
      read_obj(bytes, file, scale, vertices, triangles);
    else
      throw InputError("Parameter '" + parameter + "': '" + file
                       + "' is neither .stl nor .obj");
    require(!triangles.empty(), parameter, "'" + file + "' holds no triangles");
    return TriangleSurface(std::move(vertices.points),
                           std::move(triangles),
                           "'" + file + "' (" + parameter + ")");
  }


  TriangleSurface::TriangleSurface(std::vector<Point<3>> vertices_,
                                   Triangles             triangles_,
                                   const std::string    &what)
      : vertices(std::move(vertices_))
      , triangles(std::move(triangles_))
  {
    check_and_orient(what);
    build_tree();
  }


  void
  TriangleSurface::check_and_orient(const std::string &what)
  {
    // Each undirected edge: how often it runs each way.
    std::map<std::pair<unsigned int, unsigned int>, std::array<int, 2>> uses;
    for (unsigned int t = 0; t < triangles.size(); ++t)
      for (unsigned int k = 0; k < 3; ++k)
        {
          const unsigned int a = triangles[t][k], b = triangles[t][(k + 1) % 3];
          if (a == b)
            throw InputError(
              "Surface " + what + ": triangle " + std::to_string(t + 1) + " at "
              + describe(vertices[a]) + " has two equal vertices");
          auto &count = uses[{std::min(a, b), std::max(a, b)}];
          ++count[a < b ? 0 : 1];
        }
    std::vector<std::string> open, twisted;
    for (const auto &[edge, count] : uses)
      {
        const std::string name = describe(vertices[edge.first]) + "-"
                                 + describe(vertices[edge.second]);
        if (count[0] + count[1] != 2)
          open.push_back(
            name + " (in " + std::to_string(count[0] + count[1])
            + (count[0] + count[1] == 1 ? " triangle)" : " triangles)"));
        else if (count[0] != 1)
          twisted.push_back(name);
      }
    const auto list = [](const std::vector<std::string> &edges) {
      std::string text;
      for (unsigned int i = 0; i < std::min<std::size_t>(edges.size(), 3); ++i)
        text += (i > 0 ? ", " : "") + edges[i];
      if (edges.size() > 3)
        text += " and " + std::to_string(edges.size() - 3) + " more";
      return text;
    };
    if (!open.empty())
      throw InputError("Surface " + what
                       + " is not closed: each edge must bound exactly two "
                         "triangles, but "
                       + std::to_string(open.size())
                       + " edges do not: " + list(open));
    if (!twisted.empty())
      throw InputError("Surface " + what
                       + " is not consistently oriented: the two triangles "
                         "of each edge must run it in opposite directions, "
                         "but "
                       + std::to_string(twisted.size())
                       + " edges are run the same way: " + list(twisted));
    face_normals.resize(triangles.size());
    for (unsigned int t = 0; t < triangles.size(); ++t)
      {
        const auto        &v = triangles[t];
        const Tensor<1, 3> n
          = cross_product_3d(vertices[v[1]] - vertices[v[0]],
                             vertices[v[2]] - vertices[v[0]]);
        if (!(n.norm() > 0))
          throw InputError("Surface " + what + ": triangle "
                           + std::to_string(t + 1) + " at "
                           + describe(vertices[v[0]]) + " has zero area");
        face_normals[t] = n / n.norm();
      }
    orient_parts(what);
    // Pseudonormals (Baerentzen and Aanaes 2005).
    std::map<std::pair<unsigned int, unsigned int>, Tensor<1, 3>> edge_sum;
    vertex_normals.assign(vertices.size(), Tensor<1, 3>());
    for (unsigned int t = 0; t < triangles.size(); ++t)
      for (unsigned int k = 0; k < 3; ++k)
        {
          const unsigned int a = triangles[t][k], b = triangles[t][(k + 1) % 3],
                             c = triangles[t][(k + 2) % 3];
          edge_sum[{std::min(a, b), std::max(a, b)}] += face_normals[t];
          const Tensor<1, 3> u = vertices[b] - vertices[a],
                             w = vertices[c] - vertices[a];
          const double angle
            = std::acos(std::clamp(u * w / (u.norm() * w.norm()), -1., 1.));
          vertex_normals[a] += angle * face_normals[t];
        }
    edge_normals.resize(triangles.size());
    for (unsigned int t = 0; t < triangles.size(); ++t)
      for (unsigned int k = 0; k < 3; ++k)
        {
          const unsigned int a = triangles[t][k], b = triangles[t][(k + 1) % 3];
          edge_normals[t][k] = edge_sum[{std::min(a, b), std::max(a, b)}];
        }
  }


  void
  TriangleSurface::orient_parts(const std::string &what)
  {
    // The closed parts: triangles joined by shared edges (union-find).
    std::vector<unsigned int> part(triangles.size());
    std::iota(part.begin(), part.end(), 0u);
    const auto root = [&](unsigned int t) {
      while (part[t] != t)
        t = part[t] = part[part[t]];
      return t;
    };
    std::map<std::pair<unsigned int, unsigned int>, unsigned int> first;
    for (unsigned int t = 0; t < triangles.size(); ++t)
      for (unsigned int k = 0; k < 3; ++k)
        {
          const unsigned int a = triangles[t][k], b = triangles[t][(k + 1) % 3];
          const auto [it, added]
            = first.emplace(std::make_pair(std::min(a, b), std::max(a, b)), t);
          if (!added)
            part[root(t)] = root(it->second);
        }
    // Each part's enclosed volume: all positive (outward), or all
    // negative (inward throughout: turned); mixed signs would swap inside
    // and outside in some part.
    std::map<unsigned int, double> volumes;
    for (unsigned int t = 0; t < triangles.size(); ++t)
      volumes[root(t)] += vertices[triangles[t][0]]
                          * cross_product_3d(vertices[triangles[t][1]],
                                             vertices[triangles[t][2]]);
    unsigned int inward = 0;
    for (const auto &[p, v] : volumes)
      inward += v < 0;
    if (inward == 0)
      return;
    if (inward < volumes.size())
      throw InputError("Surface " + what + " has " + std::to_string(inward)
                       + " of its " + std::to_string(volumes.size())
                       + " closed parts oriented inward and the others "
                         "outward: orient every part outward (a hollow "
                         "obstacle, a part inside another, is not "
                         "supported)");
    for (auto &t : triangles)
      std::swap(t[1], t[2]);
    for (auto &n : face_normals)
      n = -n;
  }


  double
  TriangleSurface::volume() const
  {
    double sum = 0;
    for (const auto &t : triangles)
      sum += vertices[t[0]] * cross_product_3d(vertices[t[1]], vertices[t[2]]);
    return sum / 6;
  }


  void
  TriangleSurface::build_tree()
  {
    tree_triangles.resize(triangles.size());
    std::iota(tree_triangles.begin(), tree_triangles.end(), 0u);
    std::vector<Point<3>> centroids(triangles.size());
    for (unsigned int t = 0; t < triangles.size(); ++t)
      centroids[t] = (vertices[triangles[t][0]] + vertices[triangles[t][1]]
                      + vertices[triangles[t][2]])
                     / 3.;
    // Nodes split while they hold more than this many triangles.
    constexpr unsigned int leaf_size = 4;
    nodes.clear();
    nodes.reserve(2 * triangles.size());
    std::vector<unsigned int> pending{0};
    nodes.push_back({});
    nodes[0].count = triangles.size();
    while (!pending.empty())
      {
        const unsigned int i = pending.back();
        pending.pop_back();
        Node &node   = nodes[i];
        node.lower   = Point<3>(1e300, 1e300, 1e300);
        node.upper   = Point<3>(-1e300, -1e300, -1e300);
        Point<3> low = node.lower, high = node.upper;
        for (unsigned int j = node.first; j < node.first + node.count; ++j)
          {
            const unsigned int t = tree_triangles[j];
            for (const unsigned int v : triangles[t])
              for (unsigned int d = 0; d < 3; ++d)
                {
                  node.lower[d] = std::min(node.lower[d], vertices[v][d]);
                  node.upper[d] = std::max(node.upper[d], vertices[v][d]);
                }
            for (unsigned int d = 0; d < 3; ++d)
              {
                low[d]  = std::min(low[d], centroids[t][d]);
                high[d] = std::max(high[d], centroids[t][d]);
              }
          }
        if (node.count <= leaf_size)
          continue;
        unsigned int axis = 0;
        for (unsigned int d = 1; d < 3; ++d)
          if (high[d] - low[d] > high[axis] - low[axis])
            axis = d;
        const auto begin  = tree_triangles.begin() + node.first;
        const auto middle = begin + node.count / 2;
        std::nth_element(begin,
                         middle,
                         begin + node.count,
                         [&](const unsigned int a, const unsigned int b) {
                           return centroids[a][axis] < centroids[b][axis];
                         });
        const unsigned int first = node.first, count = node.count;
        const int          left = nodes.size();
        nodes.push_back({});
        nodes.push_back({});
        nodes[left].first     = first;
        nodes[left].count     = count / 2;
        nodes[left + 1].first = first + count / 2;
        nodes[left + 1].count = count - count / 2;
        nodes[i].left         = left;
        nodes[i].right        = left + 1;
        pending.push_back(left);
        pending.push_back(left + 1);
      }
  }


  TriangleSurface::Candidate
  TriangleSurface::nearest_on(const unsigned int t, const Point<3> &p) const
  {
    // Ericson 2005, section 5.1.5: the Voronoi regions of the vertices,
    // the edges and the face, in turn.
    const Point<3> &a = vertices[triangles[t][0]],
                   &b = vertices[triangles[t][1]],
                   &c = vertices[triangles[t][2]];
    const auto result = [&](const Point<3> &foot, const unsigned int region) {
      return Candidate{(p - foot).norm_square(), foot, t, region};
    };
    const Tensor<1, 3> ab = b - a, ac = c - a, ap = p - a;
    const double       d1 = ab * ap, d2 = ac * ap;
    if (d1 <= 0 && d2 <= 0)
      return result(a, 1);
    const Tensor<1, 3> bp = p - b;
    const double       d3 = ab * bp, d4 = ac * bp;
    if (d3 >= 0 && d4 <= d3)
      return result(b, 2);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0)
      return result(a + d1 / (d1 - d3) * ab, 4);
    const Tensor<1, 3> cp = p - c;
    const double       d5 = ab * cp, d6 = ac * cp;
    if (d6 >= 0 && d5 <= d6)
      return result(c, 3);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0)
      return result(a + d2 / (d2 - d6) * ac, 6);
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
      return result(b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b), 5);
    const double scale = 1 / (va + vb + vc);
    return result(a + vb * scale * ab + vc * scale * ac, 0);
  }


  TriangleSurface::Query
  TriangleSurface::finish(const Point<3> &y, const Candidate &best) const
  {
    Query              query;
    const unsigned int t = best.triangle;
    query.foot           = best.foot;
    const Tensor<1, 3> r = y - best.foot;
    const double       d = std::sqrt(best.distance_squared);
    if (best.region == 0)
      {
        // Beside the face: the distance field is the plane's.
        query.normal   = face_normals[t];
        query.distance = r * query.normal;
        return query;
      }
    const Tensor<1, 3> pseudonormal
      = best.region <= 3 ? vertex_normals[triangles[t][best.region - 1]]
                         : edge_normals[t][best.region - 4];
    // An edge between coplanar triangles (a quadrilateral's diagonal) or a
    // vertex amid a flat patch: the surface is a plane there, whatever
    // region the nearest point fell in (the sum of two unit normals has
    // length 2, the angle-weighted sum around a flat vertex 2 pi).
    const double flat = best.region <= 3 ? 2 * numbers::PI : 2.;
    if (pseudonormal.norm() >= flat * (1 - 1e-12))
      {
        query.normal   = face_normals[t];
        query.distance = r * query.normal;
        return query;
      }
    const double sign = r * pseudonormal >= 0 ? 1. : -1.;
    if (d == 0)
      {
        query.normal = pseudonormal / pseudonormal.norm();
        return query;
      }
    query.distance          = sign * d;
    query.normal            = sign * r / d;
    Tensor<2, 3> projection = Tensor<2, 3>(unit_symmetric_tensor<3>())
                              - outer_product(query.normal, query.normal);
    if (best.region >= 4)
      {
        // Along the edge the normal does not turn.
        const unsigned int k = best.region - 4;
        Tensor<1, 3>       e
          = vertices[triangles[t][(k + 1) % 3]] - vertices[triangles[t][k]];
        e /= e.norm();
        projection -= outer_product(e, e);
      }
    query.normal_gradient = projection / query.distance;
    return query;
  }


  TriangleSurface::Query
  TriangleSurface::query(const Point<3> &y) const
  {
    const auto box_distance_squared = [&](const Node &node) {
      double sum = 0;
      for (unsigned int d = 0; d < 3; ++d)
        {
          const double out
            = std::max({node.lower[d] - y[d], 0., y[d] - node.upper[d]});
          sum += out * out;
        }
      return sum;
    };
    Candidate        best{std::numeric_limits<double>::infinity(), y, 0, 0};
    std::vector<int> stack{0};
    stack.reserve(64);
    while (!stack.empty())
      {
        const Node &node = nodes[stack.back()];
        stack.pop_back();
        if (!(box_distance_squared(node) < best.distance_squared))
          continue;
        if (node.left < 0)
          {
            for (unsigned int j = node.first; j < node.first + node.count; ++j)
              {
                const Candidate c = nearest_on(tree_triangles[j], y);
                if (c.distance_squared < best.distance_squared)
                  best = c;
              }
            continue;
          }
        // The nearer child last, to be searched first.
        const double left  = box_distance_squared(nodes[node.left]),
                     right = box_distance_squared(nodes[node.right]);
        const int a = node.left, b = node.right;
        stack.push_back(left < right ? b : a);
        stack.push_back(left < right ? a : b);
      }
    if (!std::isfinite(best.distance_squared))
      {
        // A NaN point: NaN out, for Newton's checks.
        Query query;
        query.distance  = std::numeric_limits<double>::quiet_NaN();
        query.normal[0] = 1;
        return query;
      }
    return finish(y, best);
  }


  TriangleSurface::Query
  TriangleSurface::query_all_triangles(const Point<3> &y) const
  {
    Candidate best = nearest_on(0, y);
    for (unsigned int t = 1; t < triangles.size(); ++t)
      {
        const Candidate c = nearest_on(t, y);
        if (c.distance_squared < best.distance_squared)
          best = c;
      }
    return finish(y, best);
  }
} // namespace tissuefem::contact
