#include <tissuefem/solid/formulations/nodal_dilatation.h>
#include <tissuefem/solid/mean_dilatation.h>

namespace tissuefem::solid::formulations
{
  namespace
  {
    /// Fbar of the nodally averaged dilatation of each cell.
    template <int dim>
    class NodalDeformation : public Deformation<dim>
    {
    public:
      explicit NodalDeformation(std::vector<double> &&theta)
          : theta(std::move(theta))
      {
      }

      bool
      apply(const typename DoFHandler<dim>::active_cell_iterator &cell,
            std::vector<Tensor<2, dim>>                          &F,
            const double *,
            const unsigned int n) const override
      {
        return apply_dilatation(F, n, theta[cell->active_cell_index()]);
      }

    private:
      const std::vector<double> theta;
    };
  } // namespace


  template <int dim>
  void
  NodalDilatation<dim>::check(const Discretization<dim> &discretization,
                              const materials::MaterialSet<dim> &) const
  {
    require(discretization.simplex && discretization.fe->degree == 1,
            "Materials/Formulation",
            "'nodal dilatation' is the linear simplex's (Geometry/Cell type "
            "= simplex or a simplex mesh file, Polynomial degree = 1); use "
            "'mean dilatation' on hexahedra or P2");
  }


  template <int dim>
  void
  NodalDilatation<dim>::setup(const Context<dim> &context)
  {
    system.reset(); // refers to the patches
    patches
      = std::make_unique<solid::NodalDilatation<dim>>(context.discretization);
  }


  template <int dim>
  bool
  NodalDilatation<dim>::cell_terms(const Context<dim> &, CellTerms<dim> &) const
  {
    return false;
  }


  template <int dim>
  std::unique_ptr<Deformation<dim>>
  NodalDilatation<dim>::deformation(const Context<dim> &,
                                    const VectorType &u,
                                    const double *) const
  {
    return std::make_unique<NodalDeformation<dim>>(patches->dilatations(u));
  }


  template <int dim>
  void
  NodalDilatation<dim>::build_system(
    const Context<dim>                &context,
    const bool                         through_operators,
    const bool                         wide,
    TrilinosWrappers::SparsityPattern &sparsity)
  {
    const auto &constraints = context.discretization.constraints;
    system.reset();
    if (through_operators
        && NodalDilatationSystem<dim>::applies(*patches, constraints))
      system
        = std::make_unique<NodalDilatationSystem<dim>>(context.discretization,
                                                       *patches);
    else if (wide)
      patches->add_sparsity(constraints, sparsity);
  }


  template <int dim>
  void
  NodalDilatation<dim>::clear_system()
  {
    if (system)
      system->clear();
  }


  template <int dim>
  void
  NodalDilatation<dim>::finish_system(const MatrixType *uu,
                                      VectorType       &residual)
  {
    if (system)
      system->finish(uu, residual);
  }


  template <int dim>
  void
  NodalDilatation<dim>::solve_system(solvers::LinearSolver &solver,
                                     VectorType            &x,
                                     const VectorType      &b,
                                     const bool             refactorize)
  {
    Assert(system, ExcInternalError());
    system->solve(solver, x, b, refactorize);
  }


  template <int dim>
  void
  NodalDilatation<dim>::add_patch_terms(const Context<dim>      &context,
                                        const PatchRequest<dim> &request,
                                        MatrixType              &jacobian,
                                        VectorType              &residual,
                                        Inverted<dim>           &inverted)
  {
    Assert(!request.loads || (system && request.jacobian), ExcInternalError());
    typename NodalDilatationSystem<dim>::Loads cell_loads;
    if (request.loads)
      {
        cell_loads.inertia          = request.inertia;
        cell_loads.mass_coefficient = request.mass_coefficient;
        cell_loads.lumped_mass      = request.lumped_mass;
        cell_loads.gravity          = request.gravity;
      }
    const auto undefined
      = system ? system->assemble(*request.u,
                                  context.materials,
                                  context.fibres,
                                  *request.rows,
                                  request.inhomogeneous,
                                  request.jacobian,
                                  residual,
                                  request.loads ? &cell_loads : nullptr)
               : patches->assemble(*request.u,
                                   context.materials,
                                   context.fibres,
                                   request.jacobian,
                                   *request.rows,
                                   request.inhomogeneous,
                                   jacobian,
                                   residual);
    inverted.insert(inverted.end(), undefined.begin(), undefined.end());
  }


  template class NodalDilatation<1>;
  template class NodalDilatation<2>;
  template class NodalDilatation<3>;

  TISSUEFEM_REGISTER_FORMULATION(
    NodalDilatation,
    "nodal dilatation",
    "the locking-free linear triangle/tetrahedron (P1 only): F-bar with the "
    "dilatation averaged at the vertices over the cells around each (Bonet "
    "and Burton 1998's average nodal pressure element), which removes the "
    "volumetric locking of plain P1 with any model; its Jacobian couples "
    "each cell to the cells around its vertices' neighbours, and with a "
    "direct solver the implicit one-step methods solve it as a system with "
    "P1's stencil and the vertices' dilatation and pressure as extra "
    "unknowns.")
} // namespace tissuefem::solid::formulations
