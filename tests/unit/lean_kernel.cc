// The lean kernel of linear simplices (solid/linear_simplex_kernel.h)
// against the general quadrature loop of Solid::assemble(), for every
// registered material on triangles and tetrahedra: the implicit-step
// residual (internal force, consistent-mass inertia, gravity) and its
// Jacobian (tangent plus mass), and the internal force alone, at a random
// displacement, and the stored and kinetic energies, must agree to
// round-off (relative differences below 1e-12 in the l2 norm of the
// residual, the Frobenius norm of the matrix and the energies).
// The mesh has a clamped face (cells with constrained dofs take the
// AffineConstraints path) and, for fibre models, a fibre direction that
// varies within cells (evaluated per quadrature point) and one that is
// uniform (one evaluation per cell). The scene with 'Element kernel =
// automatic' must really use the lean kernel, and the general one not.
// The same for 'Formulation = nodal dilatation', where the kernel gives the
// inertia and gravity and the patches the elastic part (its wide Jacobian
// here), and the stored energy is evaluated once per cell.

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
        const std::string &model,
        const std::string &fibre,
        const std::string &kernel,
        const std::string &formulation)
  {
    return "set Dimension = " + std::to_string(dim) + R"(
    subsection Geometry
      set Cell type    = simplex
      set Lower corner = 0, 0, 0
      set Upper corner = 2, 1, 1
      set Subdivisions = 3, 2, 2
    end
    subsection Finite element
      set Element kernel = )"
           + kernel + R"(
    end
    subsection Materials
      set Formulation     = )"
           + formulation + R"(
      set Model           = )"
           + model + R"(
      set Young's modulus = 10
      set Poisson's ratio = 0.45
      set Density         = 2
      set Fibre direction = )"
           + fibre + R"(
    end
    subsection Boundary conditions
      set Dirichlet = 0: )"
           + std::string(dim == 2 ? "xy: 0; 0" : "xyz: 0; 0; 0") + R"(
      set Gravity = 0, -1, 0.5
    end
  )";
  }

  struct Evaluation
  {
    Vector<double>     residual, force;
    FullMatrix<double> jacobian;
    double             stored = 0, kinetic = 0;
    bool               lean   = false;
    bool               fibres = false;
  };

  template <int dim>
  Evaluation
  evaluate(const std::string &text)
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string(text);
    tissuefem_tests::SolidScene<dim> scene(prm);
    auto                            &solid = *scene.solid;
    tissuefem_tests::Random          random(20261124);
    VectorType                       u, u_tilde, r, f;
    solid.initialize_vector(u);
    solid.initialize_vector(u_tilde);
    // Strains of about 0.1: no cell inverts.
    for (const auto i : u.locally_owned_elements())
      {
        u[i]       = 0.03 * random.uniform();
        u_tilde[i] = 0.05 * random.uniform();
      }
    solid.apply_dirichlet_values(0., u);
    solid.implicit_residual(u, u_tilde, 3., 0., r, true);
    solid.internal_force(u, f);
    Evaluation result;
    result.residual = Vector<double>(r);
    result.force    = Vector<double>(f);
    const auto n    = solid.n_dofs();
    result.jacobian.reinit(n, n);
    for (const auto &entry : solid.jacobian())
      result.jacobian(entry.row(), entry.column()) = entry.value();
    result.stored  = solid.stored_energy(u);
    result.kinetic = solid.kinetic_energy(u_tilde);
    result.lean    = solid.lean_kernel_active();
    result.fibres  = solid.get_materials().any_uses_fibres();
    return result;
  }

  /// Returns whether the model uses fibres.
  template <int dim>
  bool
  compare(const std::string &model,
          const std::string &fibre,
          const std::string &label,
          const std::string &formulation = "displacement")
  {
    const Evaluation lean
      = evaluate<dim>(scene(dim, model, fibre, "automatic", formulation));
    const Evaluation general
      = evaluate<dim>(scene(dim, model, fibre, "general", formulation));
    const std::string name
      = std::to_string(dim) + "D "
        + (formulation == "displacement" ? "" : formulation + " ") + model
        + label;
    tissuefem_tests::check(lean.lean && !general.lean,
                           name + ": lean kernel used only where asked for");
    Vector<double> dr(lean.residual), df(lean.force);
    dr -= general.residual;
    df -= general.force;
    FullMatrix<double> dJ(lean.jacobian);
    dJ.add(-1., general.jacobian);
    tissuefem_tests::check_small(dr.l2_norm() / general.residual.l2_norm(),
                                 1e-12,
                                 name + ": residual, relative difference");
    tissuefem_tests::check_small(df.l2_norm() / general.force.l2_norm(),
                                 1e-12,
                                 name
                                   + ": internal force, relative difference");
    tissuefem_tests::check_small(dJ.frobenius_norm()
                                   / general.jacobian.frobenius_norm(),
                                 1e-12,
                                 name + ": Jacobian, relative difference");
    tissuefem_tests::check_small((lean.stored - general.stored)
                                   / general.stored,
                                 1e-12,
                                 name + ": stored energy, relative difference");
    tissuefem_tests::check_small((lean.kinetic - general.kinetic)
                                   / general.kinetic,
                                 1e-12,
                                 name
                                   + ": kinetic energy, relative difference");
    return general.fibres;
  }

  template <int dim>
  void
  compare_all(const std::string &formulation)
  {
    const std::string prefix
      = std::to_string(dim) + "D"
        + (formulation == "displacement" ? "" : " " + formulation);
    tissuefem_tests::EachModel each(prefix);
    for (const auto &[model, entry] :
         materials::MaterialRegistry<dim>::instance().all())
      {
        (void)entry;
        each.model(model);
        if (compare<dim>(model, "1; 0; 0", "", formulation))
          compare<dim>(model,
                       "1; x*x + y; 0.5",
                       " (fibres varying within cells)",
                       formulation);
      }
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  for (const std::string formulation : {"displacement", "nodal dilatation"})
    {
      compare_all<2>(formulation);
      compare_all<3>(formulation);
    }
  return tissuefem_tests::exit_status();
}
