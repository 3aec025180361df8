// The self-contact force (solid/self_contact.h), f = -p_c dV_o/dx with V_o
// the volume the deformed body covers more than once or negatively, checked
// by virtual work against closed forms on quadrilaterals, triangles,
// hexahedra and tetrahedra. Under the linear motion x -> x + e A x with
// tr A = dim, every volume grows by 1 + e dim to first order, so
//   sum_i f_i . A x_i = -p_c dV_o/de = -p_c dim V_o.
// A is not a multiple of the identity, so the vertices of a facet move
// differently along its normal and the identity also checks how the
// facet's force is shared among them (all on one vertex fails it).
// - Identity and a rigid quarter turn: V_o = 0, so f = 0 (every facet sees
//   winding number 1/2).
// - Mirror image (x -> -x): the body is covered -1 times, V_o = its volume
//   (1, or 0.1 in 3D): the identity holds to round-off (straight facets),
//   and the forces sum to zero (a closed boundary's area vectors do).
// - Within a step (the weights held from its start), the residual is the
//   derivative of the energy and the Jacobian that of the residual (central
//   differences, 1e-6 relative) on the spiral below moved by random
//   displacements of 1e-3, with a soft material (E = 1e-3) so that the
//   contact's terms dominate the elements'.
// - The unit square (3D: times 0.1) wound one and a half times round a
//   spiral, X -> r (cos 3 pi x, sin 3 pi x), r = 1 - 0.1 y + 0.1 x (3D:
//   z -> z + 0.075 x), on 300 x 3 (x 2) cells: the layers x and x + 2/3
//   overlap for angles in (0, pi) over a band one cell wide, 1/30 (3D: and
//   one cell high, 0.05), so V_o = pi / 30 (3D: times 0.05), times
//   sin(d) / d for the chords of the arcs, d = 3 pi / 300. The band's
//   edges follow cell faces, so every boundary facet lies wholly in or out
//   of it and the identity holds to round-off (where the band cuts
//   facets, their centres decide: an O(h) error).

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/app/parameters.h>
#include <tissuefem/contact/self_contact.h>

#include "../tests.h"
#include "solid_scene.h"

#include <iostream>
#include <set>
#include <sstream>
#include <string>

using namespace dealii;
using namespace tissuefem;

namespace
{
  /// 'Geometry/Mesh distribution' of every scene below.
  std::string mesh_distribution = "shared";

  constexpr double pressure = 7.;

  /// The virtual motion dx = A x, a general linear map with trace dim:
  /// every volume grows by 1 + e tr A = 1 + e dim. Unlike a uniform
  /// scaling it moves the vertices of a facet differently along its
  /// normal, so it sees how a facet's force is shared among them.
  template <int dim>
  Tensor<2, dim>
  stretch()
  {
    Tensor<2, dim> A;
    if constexpr (dim == 2)
      A = Tensor<2, 2>({{1.4, 0.7}, {0.3, 0.6}});
    if constexpr (dim == 3)
      A = Tensor<2, 3>({{1.4, 0.7, -0.2}, {0.3, 0.6, 0.5}, {0.1, 0.4, 1.}});
    return A;
  }

  /// The contact force's virtual work under dx = A x (stretch()) over
  /// -p_c dim V_o
  /// (1 where the force is the gradient), and its largest sum over a
  /// component over p_c times the deformed boundary's size.
  template <int dim>
  std::pair<double, double>
  virtual_work(const std::string &cells,
               const std::string &displacement,
               const unsigned int n_x,
               const double       overlap_volume)
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    const std::string upper = dim == 2 ? "1, 1" : "1, 1, 0.1";
    const std::string n = std::to_string(n_x) + (dim == 2 ? ", 3" : ", 3, 2");
    prm.parse_input_from_string(
      "set Dimension = " + std::to_string(dim)
      + "\nsubsection Geometry\n set Cell type = " + cells
      + "\n set Upper corner = " + upper + "\n set Subdivisions = " + n
      + "\n set Mesh distribution = " + mesh_distribution
      + "\nend\nsubsection Boundary conditions\n"
        " set Initial displacement = "
      + displacement + "\nend\n");
    tissuefem_tests::SolidScene<dim> scene(prm);
    const auto                      &discretization = *scene.discretization;
    VectorType                       u, v, ghosted, force, x;
    scene.solid->initial_state(u, v);
    discretization.initialize_vector(ghosted, true);
    ghosted = u;
    AffineConstraints<double> none;
    none.close();
    discretization.initialize_assembly_vector(force);
    // The force at the step's start: minus the residual's terms there.
    contact::SelfContact<dim> self_contact(discretization, pressure);
    self_contact.begin_step(ghosted, 0.);
    self_contact.add(
      ghosted, 0., false, none, false, scene.solid->jacobian(), force);
    force.compress(VectorOperation::add);
    force *= -1.;
    // Per vertex (counted by the process owning its first dof): the force
    // f_v and the deformed position x_v.
    VectorType ghosted_force;
    discretization.initialize_vector(ghosted_force, true);
    ghosted_force                = force;
    const auto            &owned = discretization.locally_owned;
    std::set<unsigned int> seen;
    Tensor<1, dim>         sum;
    double                 work = 0;
    for (const auto &cell : discretization.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          if (owned.is_element(cell->vertex_dof_index(v, 0))
              && seen.insert(cell->vertex_index(v)).second)
            {
              Tensor<1, dim> f;
              Point<dim>     x = cell->vertex(v);
              for (unsigned int c = 0; c < dim; ++c)
                {
                  f[c] = ghosted_force[cell->vertex_dof_index(v, c)];
                  x[c] += ghosted[cell->vertex_dof_index(v, c)];
                }
              sum += f;
              work += f * (stretch<dim>() * x);
            }
    sum               = Utilities::MPI::sum(sum, MPI_COMM_WORLD);
    work              = Utilities::MPI::sum(work, MPI_COMM_WORLD);
    const double size = dim == 2 ? 4 : 2 * (1 + 0.1 + 0.1);
    return {overlap_volume > 0 ? work / (-pressure * dim * overlap_volume)
                               : work / pressure,
            sum.norm() / (pressure * size)};
  }


  template <int dim>
  void
  check_cells(const std::string &cells)
  {
    const std::string z    = dim == 3 ? "; 0" : "";
    const std::string name = std::to_string(dim) + "D " + cells;
    for (const std::string &rigid : {"0; 0" + z, "-y - x; x - y" + z})
      {
        const auto [work, sum] = virtual_work<dim>(cells, rigid, 30, 0);
        tissuefem_tests::check_small(std::abs(work) + sum,
                                     1e-12,
                                     name + ", rigid motion: no force");
      }
    const double volume = dim == 2 ? 1 : 0.1;
    const auto [mirror, sum]
      = virtual_work<dim>(cells, "-2*x; 0" + z, 30, volume);
    tissuefem_tests::check_small(mirror - 1,
                                 1e-12,
                                 name + ", mirror image: work over -p dim V");
    tissuefem_tests::check_small(sum, 1e-12, name + ", mirror image: sum");
    const std::string spiral
      = "(1 - 0.1*y + 0.1*x)*cos(3*pi*x) - x; "
        "(1 - 0.1*y + 0.1*x)*sin(3*pi*x) - y"
        + (dim == 3 ? std::string("; 0.075*x") : std::string());
    // The straight facets between vertices d = 3 pi / 300 apart cut the
    // band's arcs to chords: sin(d) / d of the area.
    const double d    = 3 * M_PI / 300;
    const double band = M_PI / 30 * (dim == 3 ? 0.05 : 1) * std::sin(d) / d;
    tissuefem_tests::check_small(
      virtual_work<dim>(cells, spiral, 300, band).first - 1,
      1e-9,
      name + ", spiral: work over -p dim V_o");
  }


  /// Residual, energy and Jacobian of the solid with self contact agree
  /// within a step begun on @p displacement (see the top).
  template <int dim>
  void
  check_derivatives(const std::string &cells, const std::string &displacement)
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    const std::string upper = dim == 2 ? "1, 1" : "1, 1, 0.1";
    const std::string n     = dim == 2 ? "300, 3" : "300, 3, 2";
    prm.parse_input_from_string(
      "set Dimension = " + std::to_string(dim) + "\nsubsection Geometry\n"
      + " set Cell type = " + cells + "\n set Upper corner = " + upper
      + "\n set Subdivisions = " + n
      + "\n set Mesh distribution = " + mesh_distribution
      + "\nend\nsubsection Materials\n set Young's modulus = 1e-3\nend\n"
        "subsection Boundary conditions\n set Initial displacement = "
      + displacement + "\n set Self contact pressure = "
      + std::to_string(pressure) + "\nend\n");
    tissuefem_tests::SolidScene<dim> scene(prm);
    auto                            &solid = *scene.solid;
    VectorType                       u, v, u_tilde, d;
    solid.initial_state(u, v);
    solid.begin_step(u, 0.);
    solid.initialize_vector(u_tilde);
    solid.initialize_vector(d);
    tissuefem_tests::Random random(20261127);
    for (const auto i : u.locally_owned_elements())
      {
        u[i] = u[i] + 1e-3 * random.uniform();
        d[i] = random.uniform();
      }
    // Not a trivial pass: the overlap's facets push.
    {
      VectorType ghosted, force;
      scene.discretization->initialize_vector(ghosted, true);
      ghosted = u;
      scene.discretization->initialize_assembly_vector(force);
      AffineConstraints<double> none;
      none.close();
      contact::SelfContact<dim> self_contact(*scene.discretization, pressure);
      self_contact.begin_step(ghosted, 0.);
      self_contact.add(
        ghosted, 0., false, none, false, solid.jacobian(), force);
      force.compress(VectorOperation::add);
      tissuefem_tests::check(force.l2_norm() > 0,
                             std::to_string(dim) + "D " + cells
                               + ", spiral: the overlap pushes",
                             "no force");
    }
    tissuefem_tests::check_derivatives(solid,
                                       u,
                                       u_tilde,
                                       0.,
                                       0.,
                                       d,
                                       std::to_string(dim) + "D " + cells
                                         + ", spiral, within a step");
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  // Every figure is global (dot products of distributed vectors): one
  // process writes.
  const tissuefem_tests::OneWriter one_writer;
  // Every check again with each process holding only its own cells and
  // the layer around them: the boundary facets the force needs are
  // gathered from all processes either way.
  for (const std::string distribution : {"shared", "distributed"})
    {
      mesh_distribution = distribution;
      std::cout << "Geometry/Mesh distribution = " << distribution << std::endl;
      check_cells<2>("hypercube");
      check_cells<2>("simplex");
      check_cells<3>("hypercube");
      check_cells<3>("simplex");
      const std::string spiral2 = "(1 - 0.1*y + 0.1*x)*cos(3*pi*x) - x; "
                                  "(1 - 0.1*y + 0.1*x)*sin(3*pi*x) - y";
      check_derivatives<2>("hypercube", spiral2);
      check_derivatives<2>("simplex", spiral2);
      check_derivatives<3>("hypercube", spiral2 + "; 0.075*x");
      check_derivatives<3>("simplex", spiral2 + "; 0.075*x");
    }
  return tissuefem_tests::exit_status();
}
