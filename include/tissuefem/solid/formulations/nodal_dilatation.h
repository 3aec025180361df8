#pragma once

#include <tissuefem/solid/formulations/interface.h>
#include <tissuefem/solid/nodal_dilatation.h>
#include <tissuefem/solid/nodal_dilatation_system.h>

namespace tissuefem::solid::formulations
{
  /**
   * The locking-free linear triangle/tetrahedron (P1 only): F-bar with the
   * dilatation averaged at the vertices over the cells around each (Bonet
   * and Burton 1998's average nodal pressure element). Its elastic terms
   * couple each cell with the cells around its vertices (the patches of
   * solid::NodalDilatation); where the caller solves with a direct solver
   * only through the operators, its Newton systems are kept with P1's
   * stencil and the vertices' dilatation and pressure as extra unknowns
   * (solid::NodalDilatationSystem), else the Jacobian takes the patches'
   * wide couplings.
   */
  template <int dim>
  class NodalDilatation : public Interface<dim>
  {
  public:
    void
    check(const Discretization<dim>         &discretization,
          const materials::MaterialSet<dim> &materials) const override;

    void
    setup(const Context<dim> &context) override;

    typename Interface<dim>::LeanKernel
    lean_kernel() const override
    {
      return Interface<dim>::LeanKernel::loads;
    }

    bool
    constant_gradient() const override
    {
      return true;
    }

    /// None of the cell's own: its elastic terms are the patches'.
    bool
    cell_terms(const Context<dim> &context,
               CellTerms<dim>     &cell) const override;

    std::unique_ptr<Deformation<dim>>
    deformation(const Context<dim> &context,
                const VectorType   &u,
                const double       *carry_time) const override;

    bool
    couples_patches() const override
    {
      return true;
    }

    void
    build_system(const Context<dim>                &context,
                 const bool                         through_operators,
                 const bool                         wide,
                 TrilinosWrappers::SparsityPattern &sparsity) override;

    bool
    has_system() const override
    {
      return system != nullptr;
    }

    const MatrixType *
    system_matrix() const override
    {
      return system ? &system->system_matrix() : nullptr;
    }

    void
    clear_system() override;

    void
    finish_system(const MatrixType *uu, VectorType &residual) override;

    void
    solve_system(solvers::LinearSolver &solver,
                 VectorType            &x,
                 const VectorType      &b,
                 const bool             refactorize) override;

    void
    add_patch_terms(const Context<dim>      &context,
                    const PatchRequest<dim> &request,
                    MatrixType              &jacobian,
                    VectorType              &residual,
                    Inverted<dim>           &inverted) override;

  private:
    /// The patches of the current mesh (setup()).
    std::unique_ptr<solid::NodalDilatation<dim>> patches;
    /// The Newton systems with P1's stencil, where they serve (else null).
    std::unique_ptr<NodalDilatationSystem<dim>> system;
  };
} // namespace tissuefem::solid::formulations
