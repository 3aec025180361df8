// Obstacles that turn (contact/pose.h, 'Contact/Obstacle k/Rotation',
// 'Rotation centre' and the rotation columns of 'Motion file'), in 2D and
// 3D:
// - Gaps. Each shape (sphere, capsule, half-space, box), given a rotation
//   and a translation as expressions of t about a centre, at t = 1, against
//   the same shape placed there by its own parameters (the sphere's
//   centre, the capsule's ends and the half-space's point moved, the
//   half-space's normal turned, an axis-aligned box given as a box turned
//   by its own 'Rotation angle' and 'Rotation axis'), the expected places
//   computed here by the vector form of Rodrigues' formula; five random
//   poses (fixed seed), 40 random points each: the distance, the normal
//   and the normal's gradient agree to 1e-12.
// - A motion file of poses: rows at t = 0 and 2 with the translation and
//   the rotation linear in t give the gaps of the same linear expressions
//   at t = 0.37 and 1.5 (interpolated) and 2 at t = 3 (held); rows of the
//   wrong width are refused with the file and the line.
// - Friction turns with the obstacle: a stiff neo-Hookean block (E = 1e6,
//   nu = 0.3, rho = 1, 1 x 0.25 x 0.5 in P1 tetrahedra; a linear elastic
//   one would strain under the rotation itself) at rest on a floor (a
//   turntable) under gravity, backward Euler, dt = 0.05, the floor turned about
//   the vertical through the block's centre by 0.5 (3 t^2 - 2 t^3) rad over t
//   in [0, 1] (at rest at both ends; friction needed at most 1.7 m/s^2 times
//   the mass, below mu g = 4.9). With mu = 0.5 the block sticks and turns with
//   the table: every vertex's displacement is the table's rigid motion (R -
//   I)(X - c) to 1e-4 of the largest one, and the table's force is m g up
//   (1e-4); frictionless, the table turns under a block that stays
//   (displacements below 1e-4 of the table's). By the penalty and by the
//   augmented Lagrangian (its gap tolerance 1e-8, Newton's displacement
//   tolerance on this body: below it, Newton's own stopping leaves slips
//   that Uzawa's updates cannot settle).

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/app/parameters.h>
#include <tissuefem/base/input_error.h>
#include <tissuefem/contact/obstacle.h>

#include "../tests.h"
#include "solid_scene.h"

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

using namespace tissuefem_tests;

namespace
{
  /// "x, y[, z]" of the first dim coordinates of @p v.
  template <int dim>
  std::string
  list(const Tensor<1, dim> &v, const char *separator = ", ")
  {
    std::ostringstream s;
    s << std::setprecision(17);
    for (unsigned int d = 0; d < dim; ++d)
      s << (d ? separator : "") << v[d];
    return s.str();
  }

  /// The vector @p v turned by the rotation vector @p r (3D) or the angle
  /// r[0] (2D): v cos a + (k x v) sin a + k (k . v)(1 - cos a).
  template <int dim>
  Tensor<1, dim>
  turned(const Tensor<1, dim> &v, const Tensor<1, 3> &r)
  {
    Tensor<1, 3> w, k;
    for (unsigned int d = 0; d < dim; ++d)
      w[d] = v[d];
    double a = r[0];
    if (dim == 3)
      a = r.norm();
    k[2] = 1;
    if (dim == 3 && a > 0)
      k = r / a;
    const Tensor<1, 3> result = w * std::cos(a)
                                + cross_product_3d(k, w) * std::sin(a)
                                + k * (k * w) * (1 - std::cos(a));
    Tensor<1, dim> out;
    for (unsigned int d = 0; d < dim; ++d)
      out[d] = result[d];
    return out;
  }

  /// A pose: the rotation (vector, or angle in [0]), its centre and the
  /// translation.
  template <int dim>
  struct Motion
  {
    Tensor<1, 3>   rotation;
    Point<dim>     centre;
    Tensor<1, dim> translation;

    Point<dim>
    place(const Point<dim> &y) const
    {
      return centre + translation + turned<dim>(y - centre, rotation);
    }

    /// The slot's entries for this motion at t = 1, as expressions of t.
    std::string
    entries() const
    {
      std::ostringstream s;
      s << std::setprecision(17) << "set Rotation = ";
      for (unsigned int r = 0; r < (dim == 3 ? 3 : 1); ++r)
        s << (r ? "; " : "") << rotation[r] << " * t";
      s << "\nset Rotation centre = " << list<dim>(centre) << "\nset Motion = ";
      for (unsigned int d = 0; d < dim; ++d)
        s << (d ? "; " : "") << translation[d] << " * t";
      s << "\n";
      return s.str();
    }
  };

  /// Two obstacles: @p shape's subsection @p moved moved by @p motion, and
  /// @p placed at rest.
  template <int dim>
  std::vector<contact::Obstacle<dim>>
  obstacle_pair(const std::string &shape,
                const std::string &moved,
                const std::string &placed,
                const Motion<dim> &motion)
  {
    const std::string text
      = "set Dimension = " + std::to_string(dim)
        + "\nsubsection Contact\nsubsection Obstacle 1\n"
          "set Shape = "
        + shape + "\n" + motion.entries() + "subsection " + shape + "\n" + moved
        + "end\nend\nsubsection Obstacle 2\nset Shape = " + shape
        + "\nsubsection " + shape + "\n" + placed + "end\nend\nend\n";
    ParameterHandler prm;
    tissuefem::declare_all_parameters(prm);
    prm.parse_input_from_string(text);
    return contact::Obstacle<dim>::create_all(prm);
  }

  /// The largest difference of the two obstacles' gaps at @p points, the
  /// first at @p time, the second at rest: distance, normal, gradient.
  template <int dim>
  std::array<double, 3>
  differences(const std::vector<contact::Obstacle<dim>> &obstacles,
              const std::vector<Point<dim>>             &points,
              const double                               time = 1)
  {
    std::array<double, 3> worst{{0, 0, 0}};
    const auto            moved = obstacles[0].pose(time);
    const auto            rest  = obstacles[1].pose(0);
    for (const Point<dim> &x : points)
      {
        const auto a = obstacles[0].gap(x, moved);
        const auto b = obstacles[1].gap(x, rest);
        raise(worst[0], std::abs(a.distance - b.distance));
        raise(worst[0], std::abs(obstacles[0].distance(x, moved) - b.distance));
        raise(worst[1], (a.normal - b.normal).norm());
        raise(worst[2], (a.normal_gradient - b.normal_gradient).norm());
      }
    return worst;
  }

  template <int dim>
  void
  check_gaps()
  {
    Random            random(20261128 + dim);
    const std::string D = std::to_string(dim) + "D: ";
    std::map<std::string, std::array<double, 3>> by_shape;
    for (unsigned int trial = 0; trial < 5; ++trial)
      {
        Motion<dim> motion;
        for (unsigned int r = 0; r < 3; ++r)
          motion.rotation[r]
            = (dim == 3 || r == 0) ? 1.5 * random.uniform() : 0;
        for (unsigned int d = 0; d < dim; ++d)
          {
            motion.centre[d]      = random.uniform();
            motion.translation[d] = 0.5 * random.uniform();
          }
        std::vector<Point<dim>> points(40);
        for (auto &p : points)
          for (unsigned int d = 0; d < dim; ++d)
            p[d] = 2 * random.uniform();
        Point<dim>     a, b, q;
        Tensor<1, dim> n, half;
        for (unsigned int d = 0; d < dim; ++d)
          {
            a[d]    = 0.3 * random.uniform();
            b[d]    = a[d] + 0.8 * random.uniform();
            q[d]    = 0.5 * random.uniform();
            n[d]    = random.uniform();
            half[d] = 0.3 + 0.2 * (random.uniform() + 1);
          }
        n /= n.norm();
        const auto at = [](const Tensor<1, dim> &v) { return list<dim>(v); };
        auto       sphere
          = obstacle_pair<dim>("sphere",
                               "set Centre = " + at(a) + "\nset Radius = 0.4\n",
                               "set Centre = " + at(motion.place(a))
                                 + "\nset Radius = 0.4\n",
                               motion);
        auto capsule
          = obstacle_pair<dim>("capsule",
                               "set Start = " + at(a) + "\nset End = " + at(b)
                                 + "\nset Radius = 0.25\n",
                               "set Start = " + at(motion.place(a))
                                 + "\nset End = " + at(motion.place(b))
                                 + "\nset Radius = 0.25\n",
                               motion);
        auto half_space = obstacle_pair<dim>(
          "half-space",
          "set Point = " + at(q) + "\nset Normal = " + at(n) + "\n",
          "set Point = " + at(motion.place(q))
            + "\nset Normal = " + at(turned<dim>(n, motion.rotation)) + "\n",
          motion);
        // The box turned by its own parameters (degrees about an axis).
        const double angle
          = (dim == 3 ? motion.rotation.norm() : motion.rotation[0]) * 180
            / M_PI;
        std::ostringstream axis;
        axis << std::setprecision(17) << motion.rotation[0] << ", "
             << motion.rotation[1] << ", " << motion.rotation[2];
        std::ostringstream turned_box;
        turned_box << std::setprecision(17)
                   << "set Centre = " << at(motion.place(a))
                   << "\nset Half lengths = " << at(half)
                   << "\nset Rotation angle = " << angle
                   << "\nset Rotation axis = "
                   << (dim == 3 ? axis.str() : std::string("0, 0, 1")) << "\n";
        auto box
          = obstacle_pair<dim>("box",
                               "set Centre = " + at(a)
                                 + "\nset Half lengths = " + at(half) + "\n",
                               turned_box.str(),
                               motion);
        for (const auto &[name, obstacles] :
             {std::pair{"sphere", &sphere},
              std::pair{"capsule", &capsule},
              std::pair{"half-space", &half_space},
              std::pair{"box", &box}})
          {
            const auto d = differences<dim>(*obstacles, points);
            for (unsigned int k = 0; k < 3; ++k)
              raise(by_shape[name][k], d[k]);
          }
      }
    for (const auto &[name, d] : by_shape)
      {
        check_small(d[0], 1e-12, D + name + " turned and moved: distance");
        check_small(d[1], 1e-12, D + name + " turned and moved: normal");
        check_small(d[2],
                    1e-12,
                    D + name + " turned and moved: normal's gradient");
      }
  }

  /// Part of a motion file's check: an obstacle following @p file against
  /// one following the same poses as expressions.
  template <int dim>
  std::vector<contact::Obstacle<dim>>
  recorded(const std::string &file, const std::string &expressions)
  {
    const std::string sphere = "subsection sphere\nset Centre = 0.3, -0.2, "
                               "0.1\nset Radius = 0.4\nend\n";
    ParameterHandler  prm;
    tissuefem::declare_all_parameters(prm);
    prm.parse_input_from_string(
      "set Dimension = " + std::to_string(dim)
      + "\nsubsection Contact\nsubsection Obstacle 1\nset Shape = sphere\n"
        "set Rotation centre = 0.1, 0.2, 0.3\nset Motion file = "
      + file + "\n" + sphere
      + "end\nsubsection Obstacle 2\nset Shape = sphere\nset Rotation "
        "centre = 0.1, 0.2, 0.3\n"
      + expressions + sphere + "end\nend\n");
    return contact::Obstacle<dim>::create_all(prm);
  }

  template <int dim>
  void
  check_motion_file()
  {
    const std::string D    = std::to_string(dim) + "D: ";
    const std::string file = "poses_" + std::to_string(dim) + "d.csv";
    {
      std::ofstream out(file);
      out << "t, x, y" << (dim == 3 ? ", z, rx, ry, rz" : ", angle") << "\n"
          << "0, 0, 0" << (dim == 3 ? ", 0, 0, 0, 0" : ", 0") << "\n"
          << "2, 0.4, -0.2" << (dim == 3 ? ", 0.6, 1.2, -0.4, 0.8" : ", 1.2")
          << "\n";
    }
    const std::string expressions
      = dim == 3 ? "set Motion = 0.2*min(t, 2); -0.1*min(t, 2); 0.3*min(t, 2)\n"
                   "set Rotation = 0.6*min(t, 2); -0.2*min(t, 2); "
                   "0.4*min(t, 2)\n"
                 : "set Motion = 0.2*min(t, 2); -0.1*min(t, 2)\n"
                   "set Rotation = 0.6*min(t, 2)\n";
    const auto              obstacles = recorded<dim>(file, expressions);
    Random                  random(7 + dim);
    std::vector<Point<dim>> points(40);
    for (auto &p : points)
      for (unsigned int d = 0; d < dim; ++d)
        p[d] = 1.5 * random.uniform();
    double worst = 0;
    for (const double t : {0.37, 1.5, 3.})
      {
        const auto a = obstacles[0].pose(t), b = obstacles[1].pose(t);
        for (const Point<dim> &x : points)
          {
            const auto g = obstacles[0].gap(x, a), h = obstacles[1].gap(x, b);
            raise(worst, std::abs(g.distance - h.distance));
            raise(worst, (g.normal - h.normal).norm());
            raise(worst, (g.normal_gradient - h.normal_gradient).norm());
          }
      }
    check_small(worst,
                1e-12,
                D
                  + "poses from a file, interpolated and held, as the same "
                    "poses given as expressions");
    // Every row as wide as the first.
    {
      std::ofstream out(file);
      out << "0, 0, 0" << (dim == 3 ? ", 0, 0, 0, 0" : ", 0") << "\n"
          << "1, 0, 0" << (dim == 3 ? ", 0" : "") << "\n";
    }
    try
      {
        recorded<dim>(file, "");
        check(false, D + "a row narrower than the first is refused");
      }
    catch (const tissuefem::InputError &e)
      {
        std::cout << D << e.what() << std::endl;
      }
  }

  /// The turntable: a block at rest on the floor y = 0, the floor turned
  /// about the vertical through the block's centre by theta(t); the
  /// largest distance of a vertex's displacement from the floor's rigid
  /// motion over the largest such motion, the largest displacement over
  /// that motion, and the floor's force over m g up.
  struct Turned
  {
    double off_rigid = 0, moved = 0, force = 0;
  };

  Turned
  turntable(const std::string &method, const double mu)
  {
    const double       theta = 0.5;
    std::ostringstream text;
    text << std::setprecision(17) << R"(set Dimension = 3
      subsection Geometry
        set Cell type    = simplex
        set Lower corner = 0, 0, 0
        set Upper corner = 1, 0.25, 0.5
        set Subdivisions = 4, 1, 2
      end
      subsection Materials
        set Model           = neo-Hookean   
        set Young's modulus = 1e6
        set Poisson's ratio = 0.3
        set Density         = 1
      end
      subsection Boundary conditions
        set Load factor = 1
        set Gravity     = 0, -9.81, 0
      end
      subsection Contact
        set Method        = )"
         << method << R"(
        set Gap tolerance = 1e-8
        subsection Obstacle 1
          set Shape                = half-space
          set Name                 = turntable
          set Friction coefficient = )"
         << mu << R"(
          set Rotation        = 0; )"
         << theta << R"( * (3 * t^2 - 2 * t^3); 0
          set Rotation centre = 0.5, 0, 0.25
          subsection half-space
            set Point  = 0, 0, 0
            set Normal = 0, 1, 0
          end
        end
      end
      subsection Time integration
        set Integrator = backward Euler
        set End time   = 1
        set Time step  = 0.05
      end
    )";
    ParameterHandler prm;
    tissuefem::declare_all_parameters(prm);
    prm.parse_input_from_string(text.str());
    std::ostringstream muted;
    auto              *screen = std::cout.rdbuf(muted.rdbuf());
    Turned             result;
    {
      SolidScene<3> scene(prm);
      const auto    run = scene.start(prm);
      run->advance_to(1.);
      VectorType ghosted;
      scene.discretization->initialize_vector(ghosted, true);
      ghosted = run->state.u;
      const Point<3>     centre(0.5, 0, 0.25);
      const Tensor<1, 3> rotation({0, theta, 0});
      double             largest = 0;
      for (const auto &cell :
           scene.discretization->dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int v : cell->vertex_indices())
            {
              Tensor<1, 3> u;
              for (unsigned int c = 0; c < 3; ++c)
                u[c] = ghosted(cell->vertex_dof_index(v, c));
              const Tensor<1, 3> offset = cell->vertex(v) - centre;
              const Tensor<1, 3> rigid  = turned<3>(offset, rotation) - offset;
              raise(largest, rigid.norm());
              raise(result.off_rigid, (u - rigid).norm());
              raise(result.moved, u.norm());
            }
      const MPI_Comm comm = MPI_COMM_WORLD;
      largest             = Utilities::MPI::max(largest, comm);
      result.off_rigid = Utilities::MPI::max(result.off_rigid, comm) / largest;
      result.moved     = Utilities::MPI::max(result.moved, comm) / largest;
      const double weight = 0.125 * 9.81;
      result.force = (scene.obstacle_contact->report(ghosted, 1.)[0].force
                      - Tensor<1, 3>({0, weight, 0}))
                       .norm()
                     / weight;
    }
    std::cout.rdbuf(screen);
    return result;
  }

  void
  check_turntable()
  {
    for (const std::string method : {"penalty", "augmented Lagrangian"})
      {
        const std::string name  = "3D turntable, " + method + ": ";
        const Turned      stuck = turntable(method, 0.5);
        check_small(stuck.off_rigid,
                    1e-4,
                    name + "mu = 0.5, the block turns with the table");
        check_small(stuck.force, 1e-4, name + "the table carries m g");
        const Turned free = turntable(method, 0);
        check_small(free.moved,
                    1e-4,
                    name + "mu = 0, the table turns under the block");
      }
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check_gaps<2>();
  check_gaps<3>();
  check_motion_file<2>();
  check_motion_file<3>();
  check_turntable();
  return exit_status();
}
