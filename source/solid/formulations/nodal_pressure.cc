#include <tissuefem/base/input_error.h>
#include <tissuefem/solid/formulations/nodal_pressure.h>
#include <tissuefem/solid/nodal_dilatation_system.h>

namespace tissuefem::solid::formulations
{
  namespace
  {
    /// The model's energy and stress with the cell's own pressure pbar in
    /// place of lambda g(J): psi + g (pbar / 2 - lambda g / 2) and P +
    /// (pbar - lambda g) g' J F^{-T} (solid::NodalPressure).
    template <int dim>
    class PressureDeformation : public Deformation<dim>
    {
    public:
      PressureDeformation(std::vector<double>              &&pbar,
                          const materials::MaterialSet<dim> &materials)
          : pbar(std::move(pbar))
          , materials(materials)
      {
      }

      void
      add_own_terms(const typename DoFHandler<dim>::active_cell_iterator &cell,
                    const Tensor<2, dim>                                 &F,
                    double                                               &psi,
                    Tensor<2, dim> *P) const override
      {
        const double J = determinant(F);
        const auto   part
          = materials.material(cell->material_id()).volumetric_part(J);
        const double p = pbar[cell->active_cell_index()];
        psi += part.g * (0.5 * p - 0.5 * part.lambda * part.g);
        if (P && J != 0)
          *P += ((p - part.lambda * part.g) * part.dg * J)
                * transpose(invert(F));
      }

    private:
      const std::vector<double>          pbar;
      const materials::MaterialSet<dim> &materials;
    };
  } // namespace


  template <int dim>
  void
  NodalPressure<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Materials");
    prm.enter_subsection("Nodal pressure");
    prm.declare_entry(
      "Stabilization factor",
      "4",
      Patterns::Double(1e-3, 1e3),
      "With 'Formulation = nodal pressure': alpha in the pressure's "
      "projection stabilization, alpha/mu |p - Pi_0 p|^2 with Pi_0 the "
      "projection onto constants per cell (Dohrmann and Bochev 2004, who "
      "take 1). Larger values weaken the incompressibility constraint "
      "per vertex towards one per cell; smaller ones approach the "
      "unstable equal-order pair. doc/studies.md ('The four-unknown "
      "element') gives Cook's membrane on six triangulations for 1, 2, 4, "
      "8 and 16: 4 is the largest of them at which no triangulation's "
      "answer exceeds the converged one, as a conforming displacement "
      "element's never does.");
    prm.leave_subsection();
    prm.leave_subsection();
  }


  template <int dim>
  NodalPressure<dim>::NodalPressure(ParameterHandler &prm)
  {
    prm.enter_subsection("Materials");
    prm.enter_subsection("Nodal pressure");
    stabilization = prm.get_double("Stabilization factor");
    prm.leave_subsection();
    prm.leave_subsection();
  }


  template <int dim>
  void
  NodalPressure<dim>::check(const Discretization<dim>         &discretization,
                            const materials::MaterialSet<dim> &materials) const
  {
    require(dim >= 2 && discretization.simplex
              && discretization.fe->degree == 1,
            "Materials/Formulation",
            "'nodal pressure' is the linear triangle's and tetrahedron's "
            "(Geometry/Cell type = simplex or a simplex mesh file, "
            "Polynomial degree = 1, dimension 2 or 3); use 'mean dilatation' "
            "on hexahedra or P2");
    for (const auto &[name, model] : materials.models())
      require(model->volumetric_part(1.).lambda > 0,
              "Materials/Formulation",
              "'nodal pressure' needs a model whose energy has a volumetric "
              "part lambda/2 g(J)^2 with lambda > 0 (the neo-Hookean models, "
              "Poisson's ratio above 0); '"
                + name
                + "' has none: use 'nodal dilatation', which takes any "
                  "model");
  }


  template <int dim>
  void
  NodalPressure<dim>::setup(const Context<dim> &context)
  {
    pressure.reset(); // refers to the cells
    cells
      = std::make_unique<solid::NodalDilatation<dim>>(context.discretization);
    require(NodalDilatationSystem<dim>::applies(
              *cells, context.discretization.constraints),
            "Materials/Formulation",
            "'nodal pressure' needs a mesh without hanging nodes and each "
            "vertex's displacement numbered together");
    pressure = std::make_unique<solid::NodalPressure<dim>>(
      context.discretization, *cells, context.materials, stabilization);
  }


  template <int dim>
  bool
  NodalPressure<dim>::cell_terms(const Context<dim> &, CellTerms<dim> &) const
  {
    return false;
  }


  template <int dim>
  std::unique_ptr<Deformation<dim>>
  NodalPressure<dim>::deformation(const Context<dim> &context,
                                  const VectorType   &u,
                                  const double *) const
  {
    return std::make_unique<PressureDeformation<dim>>(
      pressure->cell_pressures(u, context.materials), context.materials);
  }


  template <int dim>
  void
  NodalPressure<dim>::build_system(const Context<dim> &context,
                                   const bool          through_operators,
                                   const bool          wide,
                                   TrilinosWrappers::SparsityPattern &)
  {
    // A Jacobian asked for without the system is a solver's error, which
    // integrators report before their first step (check_solving()); other
    // callers (benchmarks, stiffness estimates) here.
    check_solving(!wide);
    pressure->build_system(
      through_operators ? &context.discretization.constraints : nullptr);
  }


  template <int dim>
  void
  NodalPressure<dim>::check_solving(const bool through_operators) const
  {
    // Its exact Jacobian without the pressure as an unknown is dense (A^{-1}
    // couples every vertex with every other): a Jacobian is only asked for
    // without a system (wide) by solvers other than direct ones.
    require(through_operators,
            "Linear solver/Type",
            "'Materials/Formulation = nodal pressure' solves its Newton "
            "systems with a direct solver only (MUMPS, KLU or UMFPACK), "
            "by backward Euler, quasistatic or linearly implicit Euler with "
            "Newton's line search (explicit integrators need none); not with "
            "an iterative solver, Radau IIA, ARKode or the trust region");
  }


  template <int dim>
  void
  NodalPressure<dim>::clear_system()
  {
    pressure->clear();
  }


  template <int dim>
  void
  NodalPressure<dim>::finish_system(const MatrixType *uu, VectorType &residual)
  {
    if (has_system())
      pressure->finish(uu, residual);
  }


  template <int dim>
  void
  NodalPressure<dim>::solve_system(solvers::LinearSolver &solver,
                                   VectorType            &x,
                                   const VectorType      &b,
                                   const bool             refactorize)
  {
    pressure->solve(solver, x, b, refactorize);
  }


  template <int dim>
  void
  NodalPressure<dim>::add_patch_terms(const Context<dim>      &context,
                                      const PatchRequest<dim> &request,
                                      MatrixType &,
                                      VectorType    &residual,
                                      Inverted<dim> &inverted)
  {
    Assert(!request.loads, ExcInternalError());
    const auto undefined = pressure->assemble(*request.u,
                                              context.materials,
                                              context.fibres,
                                              *request.rows,
                                              request.inhomogeneous,
                                              request.jacobian,
                                              residual);
    inverted.insert(inverted.end(), undefined.begin(), undefined.end());
  }


  template class NodalPressure<1>;
  template class NodalPressure<2>;
  template class NodalPressure<3>;

  TISSUEFEM_REGISTER_FORMULATION(
    NodalPressure,
    "nodal pressure",
    "the locking-free linear triangle/tetrahedron with one pressure per "
    "vertex (P1-P1) and Dohrmann and Bochev's (2004) projection "
    "stabilization (P1 only; neo-Hookean models, whose lambda/2 g(J)^2 it "
    "replaces by the pressure): dim + 1 unknowns per vertex in its Newton "
    "systems against the nodal dilatation's dim + 2, solved with a direct "
    "solver; explicit integrators take it too.")
} // namespace tissuefem::solid::formulations
