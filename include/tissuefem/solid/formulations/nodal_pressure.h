#pragma once

#include <tissuefem/solid/formulations/interface.h>
#include <tissuefem/solid/nodal_dilatation.h>
#include <tissuefem/solid/nodal_pressure.h>

namespace tissuefem::solid::formulations
{
  /**
   * The locking-free linear triangle/tetrahedron with one pressure per
   * vertex and Dohrmann and Bochev's projection stabilization (P1 only,
   * models with a volumetric part lambda/2 g(J)^2: the neo-Hookean ones):
   * solid::NodalPressure. Its elastic terms are added after the cell loop
   * (the pressure couples every cell with every other through A^{-1});
   * its Newton systems keep the pressure as an unknown, with P1's stencil
   * and dim + 1 unknowns per vertex, solved by a direct solver.
   */
  template <int dim>
  class NodalPressure : public Interface<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    explicit NodalPressure(ParameterHandler &prm);

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
    fibre_per_cell() const override
    {
      return true;
    }

    bool
    constant_gradient() const override
    {
      return true;
    }

    /// None of the cell's own: its elastic terms follow the cell loop.
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

    void
    check_solving(const bool through_operators) const override;

    bool
    has_system() const override
    {
      return pressure && pressure->has_system();
    }

    /// Inertia and gravity come with the displacement block.
    bool
    system_takes_loads() const override
    {
      return false;
    }

    const MatrixType *
    system_matrix() const override
    {
      return has_system() ? &pressure->system_matrix() : nullptr;
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

    std::size_t
    memory_consumption() const override
    {
      return pressure ? pressure->memory_consumption() : 0;
    }

  private:
    /// 'Materials/Nodal pressure/Stabilization factor'.
    double stabilization;
    /// The P1 cells of the current mesh and the pressure on them (setup()).
    std::unique_ptr<solid::NodalDilatation<dim>> cells;
    /// Mutable: the energy's deformation() solves for the pressure.
    mutable std::unique_ptr<solid::NodalPressure<dim>> pressure;
  };
} // namespace tissuefem::solid::formulations
