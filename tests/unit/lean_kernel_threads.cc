// The lean kernel's Jacobian and residual do not depend on the number of
// threads (solid/linear_simplex_kernel.h): the cells without constraints
// add their matrices into the Trilinos rows as they are computed, in
// phases of batches that share no node (so no two threads write one
// entry, and each entry sums its cells in phase order), and the residual
// is gathered by rows in a fixed order. On meshes large enough that each
// phase is split among threads (10,000 tetrahedra, 7,200 triangles: 625
// and 450 batches of 16 cells, in some 20 phases), at a random state with a
// clamped face, the implicit-step residual and Jacobian assembled with 2
// and 4 threads, three times each, must equal the one-thread assembly
// exactly, entry by entry: a race between two threads adding to one
// entry would lose additions now and then, and a sum in another order
// would differ in its last bits. The values themselves are checked
// against the general quadrature loop in unit/lean_kernel.

#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/app/parameters.h>

#include "../tests.h"
#include "solid_scene.h"

using namespace dealii;
using namespace tissuefem;

namespace
{
  std::string
  scene(const int dim, const std::string &model)
  {
    return "set Dimension = " + std::to_string(dim) + R"(
    subsection Geometry
      set Cell type    = simplex
      set Lower corner = 0, 0, 0
      set Upper corner = 2, 1, 1
      set Subdivisions = )"
           + std::string(dim == 2 ? "60, 60" : "20, 10, 10") + R"(
    end
    subsection Materials
      set Model           = )"
           + model + R"(
      set Young's modulus = 10
      set Poisson's ratio = 0.3
      set Density         = 2
    end
    subsection Boundary conditions
      set Dirichlet = 0: )"
           + std::string(dim == 2 ? "xy: 0; 0" : "xyz: 0; 0; 0") + R"(
      set Gravity = 0, -1, 0.5
    end
  )";
  }

  /// The residual's entries, then the Jacobian's values in row order.
  template <int dim>
  std::vector<double>
  assemble(solid::Solid<dim> &solid,
           const VectorType  &u,
           const VectorType  &u_tilde)
  {
    VectorType r;
    solid.initialize_vector(r);
    solid.implicit_residual(u, u_tilde, 3., 0., r, true);
    std::vector<double> values;
    for (const auto i : r.locally_owned_elements())
      values.push_back(r[i]);
    for (const auto &entry : solid.jacobian())
      values.push_back(entry.value());
    return values;
  }

  template <int dim>
  void
  check(const std::string &model)
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string(scene(dim, model));
    tissuefem_tests::SolidScene<dim> scene(prm);
    auto                            &solid = *scene.solid;
    tissuefem_tests::Random          random(20261207);
    VectorType                       u, u_tilde;
    solid.initialize_vector(u);
    solid.initialize_vector(u_tilde);
    // Displacements of a twentieth of a cell's size: no cell inverts.
    const double h = dim == 2 ? 1. / 30 : 1. / 10;
    for (const auto i : u.locally_owned_elements())
      {
        u[i]       = 0.05 * h * random.uniform();
        u_tilde[i] = 0.1 * h * random.uniform();
      }
    solid.apply_dirichlet_values(0., u);

    MultithreadInfo::set_thread_limit(1);
    const std::vector<double> reference = assemble(solid, u, u_tilde);
    unsigned int              differing = 0;
    for (const unsigned int threads : {2u, 4u})
      for (unsigned int run = 0; run < 3; ++run)
        {
          MultithreadInfo::set_thread_limit(threads);
          differing += assemble(solid, u, u_tilde) != reference;
        }
    MultithreadInfo::set_thread_limit();
    const std::string name = std::to_string(dim) + "D " + model;
    tissuefem_tests::check(solid.lean_kernel_active(),
                           name + ": the lean kernel assembles");
    tissuefem_tests::check(differing == 0,
                           name
                             + ": residual and Jacobian with 2 and 4 "
                               "threads, three times each, equal to one "
                               "thread's in every bit",
                           std::to_string(differing)
                             + " of 6 assemblies differ");
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check<2>("neo-Hookean");
  check<3>("neo-Hookean");
  check<3>("corotational linear elastic");
  return tissuefem_tests::exit_status();
}
