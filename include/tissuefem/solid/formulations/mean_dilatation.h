#pragma once

#include <tissuefem/solid/dilatation_carry.h>
#include <tissuefem/solid/formulations/interface.h>
#include <tissuefem/solid/three_field_dilatation.h>

namespace tissuefem::solid::formulations
{
  /**
   * The F-bar form of the three-field Q1-P0 element (Simo, Taylor and
   * Pister 1985; de Souza Neto et al. 1996): Psi at Fbar = (theta/J)^(1/d)
   * F with theta the cell mean of J (solid/mean_dilatation.h), on
   * quadrilaterals/hexahedra and P2 simplices. With 'Newton
   * solver/Mean dilatation update = three field' the cell dilatation and
   * pressure are Newton unknowns of their own (ThreeFieldDilatation, the
   * IterationUnknowns here); after a mesh change the old cells'
   * dilatations may be carried (DilatationCarry). Its settings are the
   * subsection 'Materials/Mean dilatation'.
   */
  template <int dim>
  class MeanDilatation : public Interface<dim>, public IterationUnknowns
  {
  public:
    /// 'Materials/Mean dilatation' ('Update', 'Release steps'; earlier
    /// 'Newton solver/Mean dilatation update' and 'Mesh
    /// refinement/Dilatation release steps', still read).
    static void
    declare_parameters(ParameterHandler &prm);

    explicit MeanDilatation(ParameterHandler &prm);

    void
    check(const Discretization<dim>         &discretization,
          const materials::MaterialSet<dim> &materials) const override;

    void
    setup(const Context<dim> &context) override
    {
      cache = &context.cache;
    }

    std::unique_ptr<Scratch>
    make_scratch(const Context<dim> &context) const override;

    bool
    cell_terms(const Context<dim> &context,
               CellTerms<dim>     &cell) const override;

    void
    add_cell_rows(const Context<dim> &context,
                  CellTerms<dim>     &cell) const override;

    void
    assembled() override;

    std::unique_ptr<Deformation<dim>>
    deformation(const Context<dim> &context,
                const VectorType   &u,
                const double       *carry_time) const override;

    std::string
    inversion_advice() const override;

    /// With 'Update = three-field' (else the dilatation is condensed:
    /// recomputed from the displacement at every iterate).
    IterationUnknowns *
    iteration_unknowns() override
    {
      return three_field_update ? this : nullptr;
    }

    DilatationCarry<dim> *
    carry() override
    {
      return &carried;
    }

    /// IterationUnknowns; predict_update() takes the ghosted increment
    /// with its hanging values set.
    void
    begin_iterations(const double start_time) override;
    void
    predict_update(const VectorType &du) override;
    void
    set_step_length(const double alpha) override;
    void
    end_iterations(const bool converged) override;
    bool
    iterating() const override
    {
      return three_field.active();
    }

  private:
    /// The stresses (phi_F in cell.P), and with @p linearize the tangents
    /// and b = dtheta/du, C and Theta (mean_dilatation.h), at the cell
    /// dilatation @p theta; returns (V, Phi_theta).
    std::pair<double, double>
    point_terms(const Context<dim> &context,
                CellTerms<dim>     &cell,
                const double        theta,
                const bool          linearize) const;

    /// With the dilatation the cell's mean (times a carried factor).
    void
    condensed_cell(const Context<dim> &context, CellTerms<dim> &cell) const;

    /// With the cell's dilatation and pressure the three-field unknowns.
    void
    three_field_cell(const Context<dim> &context, CellTerms<dim> &cell) const;

    /// Adds pressure cof F_q to cell.P (and its derivative to cell.A).
    void
    add_cell_pressure(const double pressure, CellTerms<dim> &cell) const;

    /// Written by the assembly (one cell per thread) while iterating.
    mutable ThreeFieldDilatation three_field;
    /// The start of the step being iterated (begin_iterations()).
    double               start = 0;
    DilatationCarry<dim> carried;
    /// The cell cache, for predict_update() (setup()).
    const CellCache<dim> *cache = nullptr;
    /// 'Update = three-field'.
    bool three_field_update = true;
  };
} // namespace tissuefem::solid::formulations
