// Point location (geometry::PointLocator) and probe evaluation
// (output::Probes) on triangles and tetrahedra, against an independent
// barycentric evaluation. The field is P1 or P2 with nodal values drawn
// from a hash of each node's position and component, so it is random and
// only piecewise polynomial: a probe evaluated in the wrong cell (deal.II
// 9.4's find_active_cell_around_point tests simplices against the unit
// cube) extrapolates another cell's polynomial and misses. The reference
// value needs no deal.II: every cell is tried by its barycentric
// coordinates (computed from its vertices), and the P1 or P2 Lagrange
// basis in barycentric form, fed with the hash at the cell's vertices and
// edge midpoints, gives the value. Points: uniform in the bounding box,
// and within 1e-3 (length units) of faces, edges and vertices of random
// cells, on both sides. Points outside every cell must be refused.
// Meshes: randomly distorted boxes (fixed seeds) and SOFA's liver and
// Armadillo (data/). Also run on two processes.

#include <deal.II/base/mpi.h>
#include <deal.II/distributed/shared_tria.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/geometry/point_locator.h>
#include <tissuefem/geometry/vtu_reader.h>
#include <tissuefem/output/probes.h>
#include <tissuefem/solid/discretization.h>

#include "../tests.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

using namespace dealii;
using namespace tissuefem;

namespace
{
  /// A reproducible pseudo-random number in [-1, 1] from a position and a
  /// component: the same on every process, whatever the numbering.
  template <int dim>
  double
  field_value(const Point<dim> &x, const unsigned int component)
  {
    double s = 0.37 * component;
    for (unsigned int d = 0; d < dim; ++d)
      s += x[d] * (12.9898 + 41.23 * d);
    const double h = std::sin(s) * 43758.5453;
    return 2 * (h - std::floor(h)) - 1;
  }

  /// Barycentric coordinates of @p p in the simplex @p cell from its
  /// vertices (lambda_0 for vertex 0 ...).
  template <int dim>
  std::vector<double>
  barycentric(const typename Triangulation<dim>::active_cell_iterator &cell,
              const Point<dim>                                        &p)
  {
    FullMatrix<double> a(dim, dim), inverse(dim, dim);
    for (unsigned int v = 1; v <= dim; ++v)
      for (unsigned int d = 0; d < dim; ++d)
        a(d, v - 1) = cell->vertex(v)[d] - cell->vertex(0)[d];
    inverse.invert(a);
    Vector<double> rhs(dim), x(dim);
    for (unsigned int d = 0; d < dim; ++d)
      rhs[d] = p[d] - cell->vertex(0)[d];
    inverse.vmult(x, rhs);
    std::vector<double> lambda(dim + 1, 1.);
    for (unsigned int d = 0; d < dim; ++d)
      {
        lambda[d + 1] = x[d];
        lambda[0] -= x[d];
      }
    return lambda;
  }

  /// Component @p c at @p p by the barycentric Lagrange basis of degree
  /// @p degree in the cell containing @p p, found by trying every cell;
  /// NaN if no cell contains it (more than 1e-12 outside in barycentric
  /// terms).
  template <int dim>
  double
  reference_value(const Triangulation<dim> &mesh,
                  const unsigned int        degree,
                  const Point<dim>         &p,
                  const unsigned int        c)
  {
    double                                            best = 1e-12;
    typename Triangulation<dim>::active_cell_iterator found;
    std::vector<double>                               lambda;
    for (const auto &cell : mesh.active_cell_iterators())
      {
        const auto   l       = barycentric<dim>(cell, p);
        const double outside = -*std::min_element(l.begin(), l.end());
        if (outside < best)
          {
            best   = outside;
            found  = cell;
            lambda = l;
          }
      }
    if (lambda.empty())
      return std::numeric_limits<double>::quiet_NaN();
    double value = 0;
    for (unsigned int i = 0; i <= dim; ++i)
      {
        const double vertex = field_value(found->vertex(i), c);
        value += degree == 1 ? lambda[i] * vertex
                             : lambda[i] * (2 * lambda[i] - 1) * vertex;
        if (degree == 2)
          for (unsigned int j = i + 1; j <= dim; ++j)
            value += 4 * lambda[i] * lambda[j]
                     * field_value(Point<dim>(
                                     (found->vertex(i) + found->vertex(j)) / 2),
                                   c);
      }
    return value;
  }

  /// Test points: uniform in the mesh's bounding box, and near the faces,
  /// edges and vertices of random cells (1, 2 or dim + 1 barycentric
  /// coordinates set to give a distance between 1e-6 and 1e-3, of either
  /// sign).
  template <int dim>
  std::vector<Point<dim>>
  test_points(const Triangulation<dim> &mesh, const std::uint64_t seed)
  {
    tissuefem_tests::Random random(seed);
    std::vector<Point<dim>> points;
    const auto              box = GridTools::compute_bounding_box(mesh);
    for (unsigned int n = 0; n < 100; ++n)
      {
        Point<dim> p;
        for (unsigned int d = 0; d < dim; ++d)
          p[d] = box.lower_bound(d)
                 + (box.upper_bound(d) - box.lower_bound(d))
                     * (0.5 + 0.5 * random.uniform());
        points.push_back(p);
      }
    std::vector<typename Triangulation<dim>::active_cell_iterator> cells;
    for (const auto &cell : mesh.active_cell_iterators())
      cells.push_back(cell);
    for (unsigned int n = 0; n < 300; ++n)
      {
        const auto        &cell = cells[std::min<std::size_t>(
          cells.size() - 1, (0.5 + 0.5 * random.uniform()) * cells.size())];
        const unsigned int near
          = n % 3 == 2 ? dim : n % 3; // face, edge, vertex
        std::vector<double> lambda(dim + 1);
        double              sum = 0;
        for (auto &l : lambda)
          sum += (l = 1.5 + random.uniform());
        for (auto &l : lambda)
          l /= sum;
        // The first 'near + 1' vertices' opposite coordinates are made
        // small: a distance d from the face opposite vertex i is
        // lambda_i = d / h_i (h_i: the height over that face).
        const Point<dim>          centre    = cell->center();
        const std::vector<double> at_centre = barycentric<dim>(cell, centre);
        double                    rest      = 1;
        for (unsigned int i = 0; i <= near && i < dim; ++i)
          {
            // lambda_i is linear: its gradient by unit differences, and
            // the height over the face opposite vertex i is 1 / |grad|.
            double gradient = 0;
            for (unsigned int d = 0; d < dim; ++d)
              gradient += std::pow(
                barycentric<dim>(cell, centre + Point<dim>::unit_vector(d))[i]
                  - at_centre[i],
                2);
            const double height = 1 / std::sqrt(gradient);
            const double d
              = std::copysign(std::pow(10., -4.5 + 1.5 * random.uniform()),
                              random.uniform());
            lambda[i] = d / height;
            rest -= lambda[i];
          }
        // The remaining coordinates share the rest in their proportions.
        const unsigned int small
          = std::min(near + 1, static_cast<unsigned int>(dim));
        double others = 0;
        for (unsigned int i = small; i <= dim; ++i)
          others += lambda[i];
        Point<dim> p;
        for (unsigned int i = 0; i <= dim; ++i)
          {
            const double l = i < small ? lambda[i] : lambda[i] * rest / others;
            p += l * cell->vertex(i);
          }
        points.push_back(p);
      }
    return points;
  }

  /// A point beyond the upper corner of the mesh's bounding box.
  template <int dim>
  Point<dim>
  box_corner_beyond(const Triangulation<dim> &mesh)
  {
    const auto box = GridTools::compute_bounding_box(mesh);
    Point<dim> p   = box.get_boundary_points().second;
    for (unsigned int d = 0; d < dim; ++d)
      p[d] += 1;
    return p;
  }

  /// Probes at the test points of @p mesh against reference_value().
  template <int dim>
  void
  check_mesh(Triangulation<dim> &mesh,
             const std::string  &name,
             const std::uint64_t seed)
  {
    for (const unsigned int degree : {1u, 2u})
      {
        solid::FiniteElementParameters fe_parameters;
        fe_parameters.degree            = degree;
        fe_parameters.quadrature_points = 0;
        solid::Discretization<dim> d(mesh, fe_parameters, dim);
        // The field's nodal values: the hash at each dof's support point.
        std::vector<Point<dim>> support(d.dof_handler.n_dofs());
        DoFTools::map_dofs_to_support_points(*d.mapping,
                                             d.dof_handler,
                                             support);
        VectorType owned, u;
        d.initialize_vector(owned);
        d.initialize_vector(u, true);
        std::vector<types::global_dof_index> dofs(d.fe->n_dofs_per_cell());
        for (const auto &cell : d.dof_handler.active_cell_iterators())
          {
            cell->get_dof_indices(dofs);
            for (unsigned int k = 0; k < dofs.size(); ++k)
              if (d.locally_owned.is_element(dofs[k]))
                owned[dofs[k]]
                  = field_value(support[dofs[k]],
                                d.fe->system_to_component_index(k).first);
          }
        owned.compress(VectorOperation::insert);
        u = owned;

        const auto                       points = test_points(mesh, seed);
        std::vector<Point<dim>>          inside, outside;
        std::vector<std::vector<double>> expected;
        for (const auto &p : points)
          {
            std::vector<double> values;
            for (unsigned int c = 0; c < dim; ++c)
              values.push_back(reference_value(mesh, degree, p, c));
            if (std::isnan(values[0]))
              outside.push_back(p);
            else
              {
                inside.push_back(p);
                expected.push_back(values);
              }
          }
        // A point far outside, whatever the random points gave.
        outside.push_back(box_corner_beyond(mesh));
        const output::Probes<dim> probes(inside,
                                         *d.mapping,
                                         d.dof_handler,
                                         "Output/Probes/Points");
        const auto                values = probes.evaluate(u);
        double                    worst  = 0;
        for (unsigned int p = 0; p < inside.size(); ++p)
          for (unsigned int c = 0; c < dim; ++c)
            {
              const double error = std::abs(values[p][c] - expected[p][c]);
              tissuefem_tests::raise(worst, error);
            }
        const std::string label = name + ", P" + std::to_string(degree) + ": ";
        tissuefem_tests::check_small(worst,
                                     1e-10,
                                     label + std::to_string(inside.size())
                                       + " probes as the barycentric value");

        const geometry::PointLocator<dim> locator(*d.mapping, mesh);
        unsigned int                      found = 0;
        for (const auto &p : outside)
          found += locator.locate(p).has_value();
        tissuefem_tests::check(found == 0,
                               label + std::to_string(outside.size())
                                 + " points outside every cell: none located",
                               std::to_string(found) + " located");
        bool refused = false;
        try
          {
            output::Probes<dim>({outside.back()},
                                *d.mapping,
                                d.dof_handler,
                                "Output/Probes/Points");
          }
        catch (const InputError &e)
          {
            refused = std::string(e.what()).find("Output/Probes/Points")
                        != std::string::npos
                      && std::string(e.what()).find("outside the mesh")
                           != std::string::npos;
          }
        tissuefem_tests::check(refused,
                               label
                                 + "a probe outside: error naming "
                                   "the parameter");
      }
  }

  /// A box of simplices whose interior vertices are moved by up to 0.3
  /// of a cell (a hash of their position and @p seed).
  template <int dim>
  void
  check_distorted_box(const unsigned int n, const std::uint64_t seed)
  {
    parallel::shared::Triangulation<dim> mesh(
      MPI_COMM_WORLD,
      Triangulation<dim>::none,
      false,
      parallel::shared::Triangulation<dim>::partition_metis);
    Point<dim> corner;
    for (unsigned int d = 0; d < dim; ++d)
      corner[d] = 1;
    GridGenerator::subdivided_hyper_rectangle_with_simplices(
      mesh, std::vector<unsigned int>(dim, n), Point<dim>(), corner);
    std::vector<bool> moved(mesh.n_vertices(), false);
    for (const auto &cell : mesh.active_cell_iterators())
      for (const unsigned int v : cell->vertex_indices())
        if (!moved[cell->vertex_index(v)])
          {
            moved[cell->vertex_index(v)] = true;
            Point<dim> &x                = cell->vertex(v);
            bool        interior         = true;
            for (unsigned int d = 0; d < dim; ++d)
              interior = interior && x[d] > 1e-9 && x[d] < 1 - 1e-9;
            if (interior)
              {
                Point<dim> shift;
                for (unsigned int d = 0; d < dim; ++d)
                  shift[d] = 0.3 / n * field_value(x, d + 7 * seed);
                x += shift;
              }
          }
    check_mesh(mesh,
               std::to_string(dim) + "D box " + std::to_string(n) + "^"
                 + std::to_string(dim) + " distorted, seed "
                 + std::to_string(seed),
               seed);
  }

  void
  check_file(const std::string &file)
  {
    parallel::shared::Triangulation<3> mesh(
      MPI_COMM_WORLD,
      Triangulation<3>::none,
      false,
      parallel::shared::Triangulation<3>::partition_metis);
    const std::string path = std::string(SOURCE_DIR) + "/../../data/" + file;
    if (file.find(".vtu") != std::string::npos)
      geometry::read_vtu(path, mesh);
    else
      {
        GridIn<3>     in(mesh);
        std::ifstream stream(path);
        in.read_msh(stream);
      }
    check_mesh(mesh, file, 11);
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  // Every figure is global: one process writes.
  const tissuefem_tests::OneWriter one_writer;
  for (const std::uint64_t seed : {1, 2})
    check_distorted_box<2>(8, seed);
  for (const std::uint64_t seed : {1, 2, 3})
    check_distorted_box<3>(4, seed);
  check_file("liver.msh");
  check_file("Armadillo_Tetra_4406.vtu");
  return tissuefem_tests::exit_status();
}
