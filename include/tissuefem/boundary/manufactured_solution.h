#pragma once

#include <deal.II/base/function.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/grid/tria.h>

#include <tissuefem/base/parallel.h>
#include <tissuefem/boundary/boundary_conditions.h>
#include <tissuefem/materials/material_set.h>

namespace tissuefem::boundary
{
  /**
   * The 'Manufactured solution' subsection. When enabled, the scene's
   * boundary conditions, loads and initial state are replaced by those that
   * make a known displacement field the exact solution, so that the error
   * of a run (and its order of convergence) can be measured.
   */
  struct ManufacturedParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    bool   enabled;
    double amplitude;
    double angular_frequency;
    double wave_number;
  };

  /**
   * The manufactured displacement
   *   u_i(X, t) = A sin(omega t + phi_i) prod_d cos(k X_d + psi_id),
   * phi_i = 0.4 i, psi_id = 0.3 + 0.5 i + 0.2 d (so that no component or
   * direction is special), with the body force that makes it solve the
   * balance of momentum rho_0 u_tt = Div P(F) + b exactly:
   *   b_i = rho_0 u_tt,i - A_ijkl(F) d^2 u_k / dX_l dX_j,
   * using Div P = dP/dF : Grad F and the material's own tangent A = dP/dF
   * (exact: automatic differentiation of the energy, or closed form).
   * u and its derivatives in X and t are closed-form. Quasistatic runs
   * leave out the inertia term. The whole boundary is held at u(X, t).
   */
  template <int dim>
  class ManufacturedSolution
  {
  public:
    ManufacturedSolution(const ManufacturedParameters      &parameters,
                         const materials::MaterialSet<dim> &materials,
                         const Triangulation<dim>          &triangulation,
                         const bool                         with_inertia);

    Tensor<1, dim>
    displacement(const Point<dim> &X, const double t) const;

    Tensor<1, dim>
    velocity(const Point<dim> &X, const double t) const;

    /// Grad u (d u_i / d X_j).
    Tensor<2, dim>
    gradient(const Point<dim> &X, const double t) const;

    /// The body force per unit reference volume that makes u exact.
    Tensor<1, dim>
    body_force(const Point<dim> &X, const double t) const;

    /**
     * Replaces the Dirichlet conditions by u on every boundary id of the
     * mesh, and the body force, gravity, tractions and initial state by the
     * manufactured ones.
     */
    void
    impose_on(BoundaryConditions<dim> &conditions) const;

  private:
    ManufacturedParameters           parameters;
    const materials::Interface<dim> &material;
    double                           density;
    materials::TangentMethod         tangent_method;
    bool                             inertia;
    std::vector<types::boundary_id>  boundary_ids;

    /// sin(omega t + phi_i).
    double
    phase(const unsigned int i, const double t) const;
    /// prod_d cos(k X_d + psi_id) differentiated in X_dx1 and X_dx2 (dim:
    /// not at all).
    double
    space(const unsigned int i,
          const Point<dim>  &X,
          const unsigned int dx1,
          const unsigned int dx2) const;
  };
} // namespace tissuefem::boundary
