// The triangulated-surface shape (contact/surface.h, triangle_surface.h),
// checked against independent answers:
// - a box written as triangles, in ASCII STL, binary STL, OBJ (quadrilateral
//   faces) and ASCII STL oriented inward, against the box shape
//   (contact/box.h, its own closed form, itself checked in shape_gaps): at
//   400 random points inside and around it, the same signed distance,
//   normal and normal gradient (beside faces, beyond edges, beyond
//   corners), and the enclosed volume;
// - an icosphere (1,280 triangles): the bounding-volume tree's answer
//   equals the check of every triangle at 2,000 random points, 500 of them
//   within 1e-3 of the surface; the sign is right (inside the inscribed
//   sphere negative, outside the circumscribed positive);
// - bad surfaces get one clear error naming what is wrong: open, two
//   triangles running an edge the same way, two closed parts oriented
//   differently, a missing file, an empty file, a surface in 2D.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/app/parameters.h>
#include <tissuefem/base/input_error.h>
#include <tissuefem/contact/obstacle.h>
#include <tissuefem/contact/triangle_surface.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <iomanip>
#include <map>
#include <random>
#include <sstream>

#include "../tests.h"

using namespace dealii;
using namespace tissuefem;
using contact::TriangleSurface;

namespace
{
  // Binary STL stores floats: a box whose corners floats hold exactly.
  const Point<3>     centre(0.25, -0.125, 0.375);
  const Tensor<1, 3> half({0.5, 0.375, 0.25});

  /// The box's 8 corners and its 6 faces as outward quadrilaterals.
  std::vector<Point<3>>
  corners()
  {
    std::vector<Point<3>> result;
    for (unsigned int i = 0; i < 8; ++i)
      {
        Point<3> p = centre;
        for (unsigned int d = 0; d < 3; ++d)
          p[d] += ((i >> d) & 1 ? 1 : -1) * half[d];
        result.push_back(p);
      }
    return result;
  }

  const std::array<std::array<unsigned int, 4>, 6> quads = {{{{0, 2, 3, 1}},
                                                             {{4, 5, 7, 6}},
                                                             {{0, 1, 5, 4}},
                                                             {{2, 6, 7, 3}},
                                                             {{0, 4, 6, 2}},
                                                             {{1, 3, 7, 5}}}};

  std::vector<std::array<unsigned int, 3>>
  box_triangles(const bool inward = false)
  {
    std::vector<std::array<unsigned int, 3>> result;
    for (const auto &q : quads)
      {
        result.push_back({{q[0], q[1], q[2]}});
        result.push_back({{q[0], q[2], q[3]}});
      }
    if (inward)
      for (auto &t : result)
        std::swap(t[1], t[2]);
    return result;
  }

  void
  write_ascii_stl(const std::string                              &file,
                  const std::vector<Point<3>>                    &v,
                  const std::vector<std::array<unsigned int, 3>> &triangles)
  {
    std::ofstream out(file);
    out << std::setprecision(17) << "solid box\n";
    for (const auto &t : triangles)
      {
        out << "facet normal 0 0 0\nouter loop\n";
        for (const unsigned int i : t)
          out << "vertex " << v[i][0] << ' ' << v[i][1] << ' ' << v[i][2]
              << '\n';
        out << "endloop\nendfacet\n";
      }
    out << "endsolid box\n";
  }

  void
  write_binary_stl(const std::string &file, const std::vector<Point<3>> &v)
  {
    std::ofstream out(file, std::ios::binary);
    // A header that starts as an ASCII file does, as some exporters write.
    char header[80] = "solid written in binary";
    out.write(header, 80);
    const auto          triangles = box_triangles();
    const std::uint32_t n         = triangles.size();
    out.write(reinterpret_cast<const char *>(&n), 4);
    for (const auto &t : triangles)
      {
        float values[12] = {};
        for (unsigned int k = 0; k < 3; ++k)
          for (unsigned int d = 0; d < 3; ++d)
            values[3 + 3 * k + d] = v[t[k]][d];
        out.write(reinterpret_cast<const char *>(values), 48);
        const std::uint16_t attributes = 0;
        out.write(reinterpret_cast<const char *>(&attributes), 2);
      }
  }

  void
  write_obj(const std::string &file, const std::vector<Point<3>> &v)
  {
    std::ofstream out(file);
    out << std::setprecision(17) << "# a box\n";
    for (const auto &p : v)
      out << "v " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
    for (const auto &q : quads)
      out << "f " << q[0] + 1 << "/1/1 " << q[1] + 1 << ' ' << q[2] + 1 << ' '
          << int(q[3]) - 8 << '\n'; // a negative (relative) index too
  }

  /// The box as an obstacle of the box shape and of each file.
  void
  check_box_files()
  {
    const std::vector<Point<3>> v = corners();
    write_ascii_stl("box_ascii.stl", v, box_triangles());
    write_ascii_stl("box_inward.stl", v, box_triangles(true));
    write_binary_stl("box_binary.stl", v);
    write_obj("box.obj", v);
    const Point<3>     low = v[0], high = v[7];
    std::ostringstream text;
    text << std::setprecision(17) << "set Dimension = 3\n"
         << "subsection Contact\n subsection Obstacle 1\n  set Shape = box\n"
         << "  subsection box\n   set Centre = " << 0.5 * (low[0] + high[0])
         << ", " << 0.5 * (low[1] + high[1]) << ", " << 0.5 * (low[2] + high[2])
         << "\n   set Half lengths = " << 0.5 * (high[0] - low[0]) << ", "
         << 0.5 * (high[1] - low[1]) << ", " << 0.5 * (high[2] - low[2])
         << "\n  end\n end\n";
    const std::string              box = text.str();
    const std::vector<std::string> files
      = {"box_ascii.stl", "box_binary.stl", "box.obj", "box_inward.stl"};
    const contact::Pose<3> zero;
    for (const std::string &file : files)
      {
        ParameterHandler prm;
        declare_all_parameters(prm);
        prm.parse_input_from_string(
          box
          + " subsection Obstacle 2\n  set Shape = surface\n"
            "  set Name = file\n  subsection surface\n   set File = "
          + file + "\n  end\n end\nend\n");
        const auto   obstacles = contact::Obstacle<3>::create_all(prm);
        std::mt19937 random(17);
        std::uniform_real_distribution<double> coordinate(-1, 1);
        double distance = 0, normal = 0, curvature = 0;
        for (unsigned int i = 0; i < 400; ++i)
          {
            Point<3> y = centre;
            for (unsigned int d = 0; d < 3; ++d)
              y[d] += 2 * half[d] * coordinate(random);
            const auto expected = obstacles[0].gap(y, zero);
            const auto g        = obstacles[1].gap(y, zero);
            distance
              = std::max(distance, std::abs(g.distance - expected.distance));
            normal = std::max(normal, (g.normal - expected.normal).norm());
            // The gradient scales as 1 / distance: compare it times that.
            curvature
              = std::max(curvature,
                         (g.normal_gradient - expected.normal_gradient).norm()
                           * std::abs(expected.distance));
          }
        const std::string name = file + " against the box shape: ";
        tissuefem_tests::check_small(distance, 1e-12, name + "signed distance");
        tissuefem_tests::check_small(normal, 1e-10, name + "normal");
        tissuefem_tests::check_small(curvature,
                                     1e-10,
                                     name + "normal gradient (times |g|)");
      }
    const TriangleSurface surface
      = TriangleSurface::read("box_inward.stl", "test", 1);
    tissuefem_tests::check_small(
      surface.volume()
          / ((high[0] - low[0]) * (high[1] - low[1]) * (high[2] - low[2]))
        - 1,
      1e-12,
      "a box oriented inward: turned, its volume that of the box");
  }

  /// An icosahedron on the unit sphere, each triangle split into four
  /// @p levels times, the new vertices pushed onto the sphere.
  TriangleSurface
  icosphere(const unsigned int levels)
  {
    const double          g = (1 + std::sqrt(5.)) / 2;
    std::vector<Point<3>> v = {{-1, g, 0},
                               {1, g, 0},
                               {-1, -g, 0},
                               {1, -g, 0},
                               {0, -1, g},
                               {0, 1, g},
                               {0, -1, -g},
                               {0, 1, -g},
                               {g, 0, -1},
                               {g, 0, 1},
                               {-g, 0, -1},
                               {-g, 0, 1}};
    for (auto &p : v)
      p /= p.norm();
    std::vector<std::array<unsigned int, 3>> t
      = {{{0, 11, 5}}, {{0, 5, 1}},  {{0, 1, 7}},   {{0, 7, 10}}, {{0, 10, 11}},
         {{1, 5, 9}},  {{5, 11, 4}}, {{11, 10, 2}}, {{10, 7, 6}}, {{7, 1, 8}},
         {{3, 9, 4}},  {{3, 4, 2}},  {{3, 2, 6}},   {{3, 6, 8}},  {{3, 8, 9}},
         {{4, 9, 5}},  {{2, 4, 11}}, {{6, 2, 10}},  {{8, 6, 7}},  {{9, 8, 1}}};
    for (unsigned int level = 0; level < levels; ++level)
      {
        std::map<std::pair<unsigned int, unsigned int>, unsigned int> middle;
        const auto mid = [&](const unsigned int a, const unsigned int b) {
          const auto key = std::make_pair(std::min(a, b), std::max(a, b));
          if (const auto m = middle.find(key); m != middle.end())
            return m->second;
          Point<3> p = 0.5 * (v[a] + v[b]);
          v.push_back(p / p.norm());
          return middle[key] = v.size() - 1;
        };
        std::vector<std::array<unsigned int, 3>> finer;
        for (const auto &s : t)
          {
            const unsigned int ab = mid(s[0], s[1]), bc = mid(s[1], s[2]),
                               ca = mid(s[2], s[0]);
            finer.push_back({{s[0], ab, ca}});
            finer.push_back({{s[1], bc, ab}});
            finer.push_back({{s[2], ca, bc}});
            finer.push_back({{ab, bc, ca}});
          }
        t.swap(finer);
      }
    return TriangleSurface(v, t, "icosphere");
  }

  void
  check_tree()
  {
    const TriangleSurface                  sphere = icosphere(3);
    std::mt19937                           random(5);
    std::uniform_real_distribution<double> coordinate(-2, 2), unit(0, 1);
    double                                 difference = 0;
    bool                                   signs      = true;
    for (unsigned int i = 0; i < 2000; ++i)
      {
        Point<3> y;
        for (unsigned int d = 0; d < 3; ++d)
          y[d] = coordinate(random);
        if (i % 4 == 0)
          // Within 1e-3 of the sphere, where faces, edges and vertices
          // compete.
          y *= (1 + 2e-3 * (unit(random) - 0.5)) / y.norm();
        const auto tree = sphere.query(y);
        const auto all  = sphere.query_all_triangles(y);
        difference      = std::max(difference,
                              std::abs(tree.distance - all.distance)
                                + (tree.normal - all.normal).norm());
        if (y.norm() < 0.98)
          signs = signs && tree.distance < 0;
        if (y.norm() > 1)
          signs = signs && tree.distance > 0;
      }
    tissuefem_tests::check_small(difference,
                                 1e-14,
                                 "icosphere ("
                                   + std::to_string(sphere.n_triangles())
                                   + " triangles): the tree's nearest point is "
                                     "the check of every triangle's");
    tissuefem_tests::check(signs,
                           "icosphere: negative inside, positive outside",
                           "a sign is wrong");
  }

  void
  expect_error(const std::function<void()> &make,
               const std::string           &contains,
               const std::string           &name)
  {
    std::string message;
    try
      {
        make();
      }
    catch (const InputError &e)
      {
        message = e.what();
      }
    tissuefem_tests::check(message.find(contains) != std::string::npos,
                           name + ": the error says '" + contains + "'",
                           "message: '" + message + "'");
  }

  void
  check_errors()
  {
    const auto v    = corners();
    auto       open = box_triangles();
    open.pop_back();
    expect_error([&]() { TriangleSurface(v, open, "open box"); },
                 "is not closed",
                 "a box missing a triangle");
    auto twisted = box_triangles();
    std::swap(twisted[3][1], twisted[3][2]);
    expect_error([&]() { TriangleSurface(v, twisted, "twisted box"); },
                 "is not consistently oriented",
                 "a box with one triangle turned");
    {
      // Two boxes side by side, the second turned inside out.
      std::vector<Point<3>> two = v;
      for (const auto &p : v)
        two.push_back(p + Tensor<1, 3>({3., 0., 0.}));
      auto both = box_triangles();
      for (auto t : box_triangles(true))
        {
          for (auto &i : t)
            i += 8;
          both.push_back(t);
        }
      expect_error([&]() { TriangleSurface(two, both, "two boxes"); },
                   "closed parts oriented inward",
                   "two boxes, one turned inside out");
    }
    expect_error([&]() { TriangleSurface::read("missing.stl", "File", 1); },
                 "cannot open 'missing.stl'",
                 "a missing file");
    std::ofstream("empty.obj") << "# nothing\n";
    expect_error([&]() { TriangleSurface::read("empty.obj", "File", 1); },
                 "holds no triangles",
                 "an empty file");
    expect_error(
      [&]() {
        ParameterHandler prm;
        declare_all_parameters(prm);
        prm.parse_input_from_string(
          "set Dimension = 2\nsubsection Contact\n subsection Obstacle 1\n"
          "  set Shape = surface\n  subsection surface\n"
          "   set File = box.obj\n  end\n end\nend\n");
        contact::Obstacle<2>::create_all(prm);
      },
      "needs Dimension = 3",
      "a surface in 2D");
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check_box_files();
  check_tree();
  check_errors();
  return tissuefem_tests::exit_status();
}
