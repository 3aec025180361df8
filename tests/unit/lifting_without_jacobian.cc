// The lifting residual of a step whose factorization is kept
// (Operators::implicit_residual_lifting without the Jacobian, what the
// linearly implicit Euler asks between factorizations) against the one
// assembled with the Jacobian: on random states of P1 triangles and
// tetrahedra (the lean kernel, which lifts the moving prescribed values
// from those cells' own matrices), neo-Hookean, St Venant-Kirchhoff
// (whose compressed cells have negative diagonal entries) and corotational
// (whose cell matrices the model forms itself), consistent and
// lumped mass, with the left end clamped and the right end moved (so that
// the lifting has an increment to carry):
// - at the state whose Jacobian was assembled, the two residuals are equal
//   on every row to round-off;
// - at another state, equal on the free rows, and the kept Jacobian is
//   left as it was (its Frobenius norm unchanged, it was not assembled);
// - the lifted rows differ from the plain residual's (there is an
//   increment to carry);
// - Q1 hexahedra (the general quadrature loop) assemble the Jacobian even
//   when asked without, and say so.
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
  scene(const int          dim,
        const std::string &cells,
        const std::string &model,
        const std::string &mass)
  {
    const std::string clamp = dim == 2 ? "xy: 0; 0" : "xyz: 0; 0; 0";
    return "set Dimension = " + std::to_string(dim) + R"(
    subsection Geometry
      set Cell type    = )"
           + cells + R"(
      set Lower corner = 0, 0, 0
      set Upper corner = 2, 1, 1
      set Subdivisions = 4, 3, 2
    end
    subsection Finite element
      set Mass = )"
           + mass + R"(
    end
    subsection Materials
      set Model           = )"
           + model + R"(
      set Young's modulus = 10
      set Poisson's ratio = 0.3
      set Density         = 2
    end
    subsection Linear solver
      set Type = KLU
    end
    subsection Boundary conditions
      set Dirichlet = 0: )"
           + clamp + " | 1: x: 0.1 * t" + R"(
      set Gravity   = 0, -1, 0.5
    end
  )";
  }

  /// |a - b| / |b| over the rows @p solid leaves free (all if not
  /// @p free_only).
  template <int dim>
  double
  relative(const solid::Solid<dim> &solid,
           const VectorType        &a,
           const VectorType        &b,
           const bool               free_only)
  {
    VectorType difference(a), reference(b);
    difference -= b;
    if (free_only)
      {
        solid.zero_constrained_entries(difference);
        solid.zero_constrained_entries(reference);
      }
    return difference.l2_norm() / reference.l2_norm();
  }

  template <int dim>
  void
  check(const std::string &name, const std::string &text, const bool lean)
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string(text);
    tissuefem_tests::SolidScene<dim> scene(prm);
    auto                            &solid = *scene.solid;
    tissuefem_tests::Random          random(20261129);
    VectorType                       u, other, u_tilde;
    for (VectorType *v : {&u, &other, &u_tilde})
      {
        solid.initialize_vector(*v);
        for (const auto i : v->locally_owned_elements())
          (*v)[i] = 0.05 * random.uniform();
        v->compress(VectorOperation::insert);
        solid.apply_dirichlet_values(0., *v);
      }
    const double              c = 3., t = 1.;
    std::array<VectorType, 5> r;
    for (auto &x : r)
      solid.initialize_vector(x);

    const bool with
      = solid.implicit_residual_lifting(u, u_tilde, c, t, r[0], true);
    const bool without
      = solid.implicit_residual_lifting(u, u_tilde, c, t, r[1], false);
    tissuefem_tests::check(with && without == !lean,
                           name
                             + ": the Jacobian is assembled unless the lean "
                               "kernel lifts without it");
    tissuefem_tests::check_small(relative(solid, r[1], r[0], false),
                                 1e-13,
                                 name
                                   + ": at the Jacobian's state, every row "
                                     "as with the Jacobian");

    solid.implicit_residual_lifting(u, u_tilde, c, t, r[0], true);
    const double kept = solid.jacobian().frobenius_norm();
    solid.implicit_residual_lifting(other, u_tilde, c, t, r[2], false);
    const double after = solid.jacobian().frobenius_norm();
    solid.implicit_residual_lifting(other, u_tilde, c, t, r[3], true);
    tissuefem_tests::check_small(relative(solid, r[2], r[3], true),
                                 1e-13,
                                 name
                                   + ": at another state, the free rows as "
                                     "with the Jacobian");
    tissuefem_tests::check(!lean || after == kept,
                           name + ": the kept Jacobian is left as it was");
    solid.implicit_residual(other, u_tilde, c, t, r[4], false);
    tissuefem_tests::check(relative(solid, r[2], r[4], true) > 1e-3,
                           name
                             + ": the lifted rows differ from the plain "
                               "residual's",
                           std::to_string(relative(solid, r[2], r[4], true)));
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const tissuefem_tests::OneWriter one_writer;
  for (const std::string mass : {"consistent", "lumped"})
    {
      check<2>("P1 triangles, neo-Hookean, " + mass + " mass",
               scene(2, "simplex", "neo-Hookean", mass),
               true);
      check<3>("P1 tetrahedra, neo-Hookean, " + mass + " mass",
               scene(3, "simplex", "neo-Hookean", mass),
               true);
      check<3>("P1 tetrahedra, St Venant-Kirchhoff, " + mass + " mass",
               scene(3, "simplex", "St Venant-Kirchhoff", mass),
               true);
      check<3>("P1 tetrahedra, corotational, " + mass + " mass",
               scene(3, "simplex", "corotational linear elastic", mass),
               true);
    }
  check<3>("Q1 hexahedra, neo-Hookean",
           scene(3, "hypercube", "neo-Hookean", "consistent"),
           false);
  return tissuefem_tests::exit_status();
}
