// The rigid shapes of contact (contact/*.h) answer with a signed distance,
// its gradient (the normal) and the normal's gradient (the curvature term
// of the contact tangent). Checked for each shape, in 2D and 3D:
// - closed-form distances at chosen points (beside a face, an edge, a
//   corner, inside; beside a capsule's shaft and beyond its tip), written
//   by hand from the geometry;
// - at 400 random points around it (fixed seed): |n| = 1; n is the
//   distance's gradient and the normal gradient the normal's, both by
//   central differences; the distance alone (Shape::distance()) is the
//   gap's; and y - g n, the foot of the point, lies on the
//   surface (gap 0), and 1e-3 off it along n the gap is 1e-3 with the
//   same normal: the properties that make g a
//   signed distance and not merely a function that vanishes on the
//   surface.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/app/parameters.h>
#include <tissuefem/contact/obstacle.h>

#include <cmath>

#include "../tests.h"

using namespace dealii;
using namespace tissuefem;

namespace
{
  /// Three obstacles: a capsule from (0, 0, 0) to (0, 2, 0) of radius 0.5,
  /// an axis-aligned box about (3, 0, 0) of half lengths (1, 0.5, 0.25), and
  /// that box turned by 30 degrees about (1, 1, 1) (about z in 2D) and
  /// centred at (-3, 1, 0.5).
  const char *shapes = R"(
    subsection Contact
      subsection Obstacle 1
        set Shape = capsule
        subsection capsule
          set Start  = 0, 0, 0
          set End    = 0, 2, 0
          set Radius = 0.5
        end
      end
      subsection Obstacle 2
        set Shape = box
        set Name  = aligned box
        subsection box
          set Centre       = 3, 0, 0
          set Half lengths = 1, 0.5, 0.25
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
    end
  )";

  template <int dim>
  Point<dim>
  point(const double x, const double y, const double z = 0)
  {
    const double c[] = {x, y, z};
    Point<dim>   p;
    for (unsigned int d = 0; d < dim; ++d)
      p[d] = c[d];
    return p;
  }

  template <int dim>
  Tensor<1, dim>
  unit_vector(const unsigned int d)
  {
    Tensor<1, dim> e;
    e[d] = 1;
    return e;
  }

  template <int dim>
  void
  check_values(const std::vector<contact::Obstacle<dim>> &obstacles)
  {
    const std::string D = std::to_string(dim) + "D: ";
    const auto        g = [&](const unsigned int o, const Point<dim> &y) {
      return obstacles[o].gap(y, contact::Pose<dim>()).distance;
    };
    const double s2 = std::sqrt(2.), s3 = std::sqrt(3.);
    // Capsule: beside the shaft, beyond the tip (diagonally), on the axis.
    tissuefem_tests::check_small(g(0, point<dim>(1.5, 1)) - 1,
                                 1e-14,
                                 D + "capsule beside its shaft");
    tissuefem_tests::check_small(g(0, point<dim>(1, 3)) - (s2 - 0.5),
                                 1e-14,
                                 D + "capsule beyond its tip");
    tissuefem_tests::check_small(g(0, point<dim>(0, 0.7)) + 0.5,
                                 1e-14,
                                 D + "capsule on its axis");
    // Aligned box: beside a face, beyond an edge, inside near the face y.
    tissuefem_tests::check_small(g(1, point<dim>(4.5, 0.1)) - 0.5,
                                 1e-14,
                                 D + "box beside a face");
    tissuefem_tests::check_small(g(1, point<dim>(5, 1.5)) - s2,
                                 1e-14,
                                 D + "box beyond an edge");
    tissuefem_tests::check_small(g(1, point<dim>(3.2, 0.4)) + 0.1,
                                 1e-14,
                                 D + "box inside");
    if constexpr (dim == 3)
      tissuefem_tests::check_small(g(1, point<dim>(5, 1.5, 1.25)) - s3,
                                   1e-14,
                                   D + "box beyond a corner");
    // Turned box: a point on its first axis, 0.5 beyond its face.
    Tensor<1, dim> first;
    if constexpr (dim == 2)
      first = point<dim>(std::cos(M_PI / 6), std::sin(M_PI / 6));
    else
      {
        // Rodrigues for e_x about (1, 1, 1) / sqrt 3 by 30 degrees:
        // cos e_x + sin k x e_x + (1 - cos) (k . e_x) k.
        const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
        first = point<dim>(c + (1 - c) / 3,
                           s / s3 + (1 - c) / 3,
                           -s / s3 + (1 - c) / 3);
      }
    tissuefem_tests::check_small(g(2, point<dim>(-3, 1, 0.5) + 1.5 * first)
                                   - 0.5,
                                 1e-14,
                                 D + "turned box along its axis");
  }

  template <int dim>
  void
  check_fields(const std::vector<contact::Obstacle<dim>> &obstacles)
  {
    const Point<dim> centres[]
      = {point<dim>(0, 1, 0), point<dim>(3, 0, 0), point<dim>(-3, 1, 0.5)};
    tissuefem_tests::Random random(20261126);
    const double            h = 1e-6;
    for (unsigned int o = 0; o < obstacles.size(); ++o)
      {
        const auto gap = [&](const Point<dim> &y) {
          return obstacles[o].gap(y, contact::Pose<dim>());
        };
        double unit = 0, gradient = 0, curvature = 0, foot = 0, foot_normal = 0,
               alone = 0;
        for (unsigned int k = 0; k < 400; ++k)
          {
            Point<dim> y = centres[o];
            for (unsigned int d = 0; d < dim; ++d)
              y[d] += 2 * random.uniform();
            const auto g = gap(y);
            tissuefem_tests::raise(unit, std::abs(g.normal.norm() - 1));
            tissuefem_tests::raise(
              alone,
              std::abs(obstacles[o].distance(y, contact::Pose<dim>()) - g.distance));
            for (unsigned int d = 0; d < dim; ++d)
              {
                Point<dim> plus = y, minus = y;
                plus[d] += h;
                minus[d] -= h;
                const auto gp = gap(plus), gm = gap(minus);
                tissuefem_tests::raise(gradient,
                                       std::abs((gp.distance - gm.distance)
                                                  / (2 * h)
                                                - g.normal[d]));
                const Tensor<1, dim> dn
                  = (gp.normal - gm.normal) / (2 * h)
                    - g.normal_gradient * unit_vector<dim>(d);
                tissuefem_tests::raise(curvature, dn.norm());
              }
            const auto f = gap(y - g.distance * g.normal);
            tissuefem_tests::raise(foot, std::abs(f.distance));
            // Off the foot along n (where the foot is an edge or a
            // corner, the normal there is one of several).
            const auto off = gap(y + (1e-3 - g.distance) * g.normal);
            tissuefem_tests::raise(foot_normal,
                                   std::abs(off.distance - 1e-3)
                                     + (off.normal - g.normal).norm());
          }
        const std::string name
          = std::to_string(dim) + "D " + obstacles[o].name + ": ";
        tissuefem_tests::check_small(unit, 1e-12, name + "|n| = 1");
        tissuefem_tests::check_small(alone,
                                     1e-15,
                                     name + "the distance alone is the gap's");
        tissuefem_tests::check_small(gradient, 1e-6, name + "n = grad g");
        tissuefem_tests::check_small(curvature,
                                     1e-5,
                                     name + "normal gradient = grad n");
        tissuefem_tests::check_small(
          foot, 1e-12, name + "the foot y - g n lies on the surface");
        tissuefem_tests::check_small(
          foot_normal,
          1e-9,
          name + "1e-3 off the foot along n: gap 1e-3, normal n");
      }
  }

  template <int dim>
  void
  check()
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string("set Dimension = " + std::to_string(dim)
                                + shapes);
    const auto obstacles = contact::Obstacle<dim>::create_all(prm);
    check_values(obstacles);
    check_fields(obstacles);
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check<2>();
  check<3>();
  return tissuefem_tests::exit_status();
}
