// The nodal dilatation's Newton systems solved through the sparser system
// with vertex unknowns (solid/nodal_dilatation_system.h) give the same
// updates as the wide exact Jacobian (whose derivatives element_consistency
// checks against central differences), and its residual is the same: on
// random states of P1 triangles and tetrahedra, for Newton's homogeneous
// rows, for the lifting of a Dirichlet increment (implicit_residual_lifting),
// and for the residual alone, with MUMPS, KLU and UMFPACK (one process).
// Figures are relative differences, bounded by round-off.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/app/parameters.h>

#include "../tests.h"
#include "solid_scene.h"

using namespace dealii;
using namespace tissuefem;

namespace
{
  std::string
  scene(const int dim, const std::string &model, const std::string &solver)
  {
    const std::string clamp = dim == 2 ? "xy: 0; 0" : "xyz: 0; 0; 0";
    // The left end clamped, the right end moved at time 1 (so that the
    // lifting has an increment to carry), a traction on top.
    return "set Dimension = " + std::to_string(dim) + R"(
    subsection Geometry
      set Cell type    = simplex
      set Lower corner = 0, 0, 0
      set Upper corner = 2, 1, 1
      set Subdivisions = 4, 3, 2
    end
    subsection Materials
      set Model           = )"
           + model + R"(
      set Young's modulus = 10
      set Poisson's ratio = 0.499
      set Density         = 2
      set Formulation     = nodal dilatation
    end
    subsection Linear solver
      set Type = )"
           + solver + R"(
    end
    subsection Boundary conditions
      set Dirichlet = 0: )"
           + clamp + " | 1: x: 0.1 * t" + R"(
      set Gravity   = 0, -1, 0.5
    end
  )";
  }

  double
  relative(const VectorType &a, const VectorType &b)
  {
    VectorType difference(a);
    difference -= b;
    return difference.l2_norm() / b.l2_norm();
  }

  template <int dim>
  void
  check(const std::string &name, const std::string &text)
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string(text);
    tissuefem_tests::SolidScene<dim> scene(prm);
    auto                            &solid  = *scene.solid;
    auto                            &solver = *scene.linear_solver;
    tissuefem_tests::Random          random(20261127);
    VectorType                       u, u_tilde;
    solid.initialize_vector(u);
    solid.initialize_vector(u_tilde);
    for (const auto i : u.locally_owned_elements())
      {
        u[i]       = 0.1 * random.uniform();
        u_tilde[i] = 0.05 * random.uniform();
      }
    solid.apply_dirichlet_values(0., u);
    const double c = 3., t = 1.;

    // Wide first, then the system; each returns (residual, lifted
    // residual, Newton update, lifting update, residual alone).
    const auto solve = [&](const bool through_system) {
      solid.solve_only_through_operators(through_system, solver);
      std::array<VectorType, 5> v;
      for (auto &x : v)
        solid.initialize_vector(x);
      VectorType b;
      solid.implicit_residual(u, u_tilde, c, t, v[0], true);
      b = v[0];
      b *= -1.;
      solid.solve_jacobian(solver, v[2], b, true, 0.);
      solid.implicit_residual_lifting(u, u_tilde, c, t, v[1], true);
      b = v[1];
      b *= -1.;
      solid.solve_jacobian(solver, v[3], b, true, 0.);
      solid.implicit_residual(u, u_tilde, c, t, v[4], false);
      return v;
    };
    const auto wide   = solve(false);
    const auto system = solve(true);
    double     worst  = 0;
    tissuefem_tests::raise(worst, relative(system[0], wide[0]));
    tissuefem_tests::raise(worst, relative(system[4], wide[0]));
    tissuefem_tests::check_small(worst,
                                 1e-12,
                                 name
                                   + ": residual, with the Jacobian and "
                                     "alone, as the patches give it");
    worst = 0;
    tissuefem_tests::raise(worst, relative(system[2], wide[2]));
    tissuefem_tests::check_small(worst, 1e-9, name + ": Newton update");
    worst = 0;
    tissuefem_tests::raise(worst, relative(system[3], wide[3]));
    tissuefem_tests::check_small(worst,
                                 1e-9,
                                 name
                                   + ": update lifting the Dirichlet "
                                     "increment");
    // The lifted update carries the increment exactly (0.1 in x on the
    // right end), in either form; deal.II 9.4's lifting alone would not
    // where a cell's diagonal entry is negative (St Venant-Kirchhoff).
    for (const auto *update : {&wide[3], &system[3]})
      {
        VectorType moved(u), prescribed;
        moved += *update;
        prescribed = moved;
        solid.apply_dirichlet_values(t, prescribed);
        prescribed -= moved;
        tissuefem_tests::check_small(
          prescribed.linfty_norm() / 0.1,
          1e-12,
          name + ": the lifted state meets the Dirichlet values, "
            + (update == &wide[3] ? "wide" : "system"));
      }
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const tissuefem_tests::OneWriter one_writer;
  for (const std::string solver : {"MUMPS", "KLU", "UMFPACK"})
    {
      if (solver == "UMFPACK"
          && Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
        continue;
      check<2>("P1 triangles, neo-Hookean, " + solver,
               scene(2, "neo-Hookean", solver));
      check<3>("P1 tetrahedra, robust neo-Hookean, " + solver,
               scene(3, "robust neo-Hookean", solver));
    }
  check<3>("P1 tetrahedra, St Venant-Kirchhoff, MUMPS",
           scene(3, "St Venant-Kirchhoff", "MUMPS"));
  return tissuefem_tests::failures() == 0 ? 0 : 1;
}
