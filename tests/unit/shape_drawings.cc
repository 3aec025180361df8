// What the live view draws of each rigid shape (Shape::drawing(), through
// Obstacle::drawing()), in 2D and 3D: the triangles lie on the shape, are
// turned outwards, and enclose what the shape encloses. Checked against
// the shapes' own signed distances and closed forms written here:
// - every drawn corner of a bounded shape lies on its surface (gap 0; in
//   2D the fan's centre lies inside); a half-space's square lies in its
//   plane, centred at the foot of the given centre;
// - each triangle's normal points out of the shape: the gap grows along
//   it (3D), or the triangle is counter-clockwise (2D);
// - the enclosed area or volume: the box's exactly (2^dim times the
//   product of its half lengths); the disc's and the stadium's as the
//   inscribed polygon's, (n / 2) R^2 sin(2 pi / n) (+ 2 R L); a ball's and
//   a capsule's between 0.97 times the exact volume and the exact volume
//   (an inscribed polyhedron); an octahedron read from OBJ exactly
//   (4/3 a^3);
// - where the page puts a drawing: for a box turned, rotating about a
//   centre of its own and moving, at t = 0.7, every corner placed by the
//   frames' translation and rotation (ObstacleView::placement(), x = t' +
//   R y) is where contact's pose puts it (Pose::world()).

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/app/parameters.h>
#include <tissuefem/contact/obstacle.h>
#include <tissuefem/output/obstacle_view.h>

#include <cmath>
#include <fstream>

#include "../tests.h"

using namespace dealii;
using namespace tissuefem;

namespace
{
  const char *shapes = R"(
    subsection Contact
      subsection Obstacle 1
        set Shape = sphere
        set Name  = ball
        subsection sphere
          set Centre = 1, 2, 3
          set Radius = 0.5
        end
      end
      subsection Obstacle 2
        set Shape = capsule
        set Name  = shaft
        subsection capsule
          set Start  = 0, 0, 0
          set End    = 0.6, 0.8, 0
          set Radius = 0.25
        end
      end
      subsection Obstacle 3
        set Shape = box
        set Name  = turned box
        subsection box
          set Centre         = -3, 1, 0.5
          set Half lengths   = 1, 0.5, 0.25
          set Rotation angle = 30
          set Rotation axis  = 1, 1, 1
        end
      end
      subsection Obstacle 4
        set Shape = half-space
        set Name  = floor
        subsection half-space
          set Point  = 0, -1, 0
          set Normal = 1, 1, 0
        end
      end
    end
  )";

  const char *octahedron = R"(
    subsection Contact
      subsection Obstacle 5
        set Shape = surface
        set Name  = octahedron
        subsection surface
          set File = shape_drawings_octahedron.obj
        end
      end
    end
  )";

  template <int dim>
  std::string
  prefix(const contact::Obstacle<dim> &o)
  {
    return std::to_string(dim) + "D " + o.name + ": ";
  }

  /// A turned box that rotates about (1, 0.5, -0.2) and moves.
  std::string
  turning(const int dim)
  {
    return std::string(R"(
    subsection Contact
      subsection Obstacle 6
        set Shape           = box
        set Name            = turning box
        set Motion          = 0.3*t; -0.1; 0.2
        set Rotation centre = 1, 0.5, -0.2
        set Rotation        = )")
           + (dim == 2 ? "0.4*t + 0.1" : "0.1*t; 0.3; -0.2*t") + R"(
        subsection box
          set Centre         = 2, -1, 0.5
          set Half lengths   = 0.5, 0.25, 1
          set Rotation angle = 20
          set Rotation axis  = 0, 1, 1
        end
      end
    end
  )";
  }

  /// The page's placement of a drawing against contact's pose.
  template <int dim>
  void
  check_placement(const contact::Obstacle<dim> &o)
  {
    const auto           pose  = o.pose(0.7);
    const Tensor<1, dim> shift = output::ObstacleView<dim>::placement(pose);
    double               error = 0;
    for (const auto &y : o.drawing(Point<dim>(), 4).vertices)
      tissuefem_tests::raise(
        error, (shift + pose.rotation * y - pose.world(y)).norm());
    tissuefem_tests::check(pose.rotates, prefix(o) + "rotates at t = 0.7", "");
    tissuefem_tests::check_small(error,
                                 1e-12,
                                 prefix(o)
                                   + "corners placed as contact's pose puts "
                                     "them");
  }

  /// The closed-form area (2D) or volume (3D), and whether the drawing
  /// is inscribed (then only bounded: [0.97, 1] of it).
  template <int dim>
  std::pair<double, bool>
  exact_measure(const std::string &name)
  {
    const double n = contact::drawing::segments;
    if (name == "ball")
      return dim == 2
               ? std::make_pair(n / 2 * 0.25 * std::sin(2 * M_PI / n), false)
               : std::make_pair(4. / 3 * M_PI * 0.125, true);
    if (name == "shaft")
      return dim == 2
               ? std::make_pair(2 * 0.25 * 1
                                  + n / 2 * 0.0625 * std::sin(2 * M_PI / n),
                                false)
               : std::make_pair(M_PI * 0.0625 * 1 + 4. / 3 * M_PI * 0.015625,
                                true);
    if (name == "turned box")
      return {dim == 2 ? 2. * 1. : 8. * 0.125, false};
    if (name == "octahedron")
      return {4. / 3 * 8, false};
    return {0, false};
  }

  template <int dim>
  void
  check_obstacle(const contact::Obstacle<dim> &o)
  {
    const Point<dim> centre;
    const double     extent = 4;
    const auto       d      = o.drawing(centre, extent);
    const auto       pose   = o.pose(0.);
    const auto       gap
      = [&](const Point<dim> &y) { return o.gap(y, pose).distance; };
    const std::string name = prefix(o);
    bool valid = !d.triangles.empty() && d.triangles.size() % 3 == 0;
    for (const unsigned int v : d.triangles)
      valid = valid && v < d.vertices.size();
    tissuefem_tests::check(valid, name + "triangles of its corners", "");
    if (!valid)
      return;

    // Corners on the surface (or in the plane); a 2D fan's centre inside.
    double on_surface = 0, inside = -1;
    for (unsigned int v = 0; v < d.vertices.size(); ++v)
      {
        const double g = gap(d.vertices[v]);
        if (o.name == "floor" && dim == 2 && v >= 2)
          tissuefem_tests::raise(on_surface, std::abs(g + extent / 10));
        else if (dim == 2 && v == 0 && (o.name == "ball" || o.name == "shaft"))
          inside = g;
        else
          tissuefem_tests::raise(on_surface, std::abs(g));
      }
    tissuefem_tests::check_small(on_surface, 1e-12, name + "corners on it");
    if (dim == 2 && (o.name == "ball" || o.name == "shaft"))
      tissuefem_tests::check(inside < 0, name + "fan centre inside", "");

    // Outward, triangle by triangle.
    unsigned int inward = 0;
    for (unsigned int t = 0; t < d.triangles.size(); t += 3)
      {
        const Point<dim> &a = d.vertices[d.triangles[t]];
        const Point<dim> &b = d.vertices[d.triangles[t + 1]];
        const Point<dim> &c = d.vertices[d.triangles[t + 2]];
        if constexpr (dim == 2)
          inward += ((b - a)[0] * (c - a)[1] - (b - a)[1] * (c - a)[0]) <= 0;
        else
          {
            Tensor<1, 3> n = cross_product_3d(b - a, c - a);
            n /= n.norm();
            const Point<3> m = (a + b + c) / 3;
            inward += gap(m + 1e-3 * n) <= gap(m - 1e-3 * n);
          }
      }
    tissuefem_tests::check(inward == 0,
                           name + "every triangle turned outwards",
                           std::to_string(inward) + " inward");

    const double measure = contact::drawing::enclosed_measure(d);
    if (o.name == "floor")
      {
        // The square (3D) is centred at the foot of the centre, (0.5, -0.5,
        // 0) for the plane x + y = -1, with side extent.
        Point<dim> mean;
        for (unsigned int v = 0; v < (dim == 3 ? 4u : 2u); ++v)
          mean += d.vertices[v] / (dim == 3 ? 4. : 2.);
        Point<dim> foot;
        foot[0] = foot[1] = -0.5;
        tissuefem_tests::check_small((mean - foot).norm(),
                                     1e-12,
                                     name + "centred at the foot");
        const double expected = dim == 2 ? extent * extent / 10 : 0;
        if (dim == 2)
          tissuefem_tests::check_small(measure / expected - 1,
                                       1e-12,
                                       name + "area extent^2 / 10");
        return;
      }
    const auto [exact, inscribed] = exact_measure<dim>(o.name);
    if (inscribed)
      tissuefem_tests::check(measure <= exact && measure >= 0.97 * exact,
                             name + "encloses 0.97-1 of the closed form",
                             std::to_string(measure / exact));
    else
      tissuefem_tests::check_small(measure / exact - 1,
                                   1e-12,
                                   name + "encloses the closed form");
  }

  template <int dim>
  void
  check()
  {
    // Slots up to 6, as a parameter file naming them would declare.
    contact::name_obstacle_slot("6", "shape_drawings");
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string("set Dimension = " + std::to_string(dim)
                                + shapes + (dim == 3 ? octahedron : "")
                                + turning(dim));
    for (const auto &o : contact::Obstacle<dim>::create_all(prm, "."))
      if (o.name == "turning box")
        check_placement(o);
      else
        check_obstacle(o);
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  {
    // The regular octahedron with corners (+-2, 0, 0), ..., faces outward.
    std::ofstream obj("shape_drawings_octahedron.obj");
    obj << "v 2 0 0\nv -2 0 0\nv 0 2 0\nv 0 -2 0\nv 0 0 2\nv 0 0 -2\n"
           "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\n"
           "f 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";
  }
  check<2>();
  check<3>();
  return tissuefem_tests::exit_status();
}
