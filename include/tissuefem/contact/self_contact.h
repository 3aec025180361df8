#pragma once

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>

#include <tissuefem/forces/registry.h>
#include <tissuefem/solid/discretization.h>

#include <boost/signals2/connection.hpp>

#include <array>
#include <vector>

namespace tissuefem::contact
{
  /**
   * Self contact by overlap volume ('Boundary conditions/Self contact
   * pressure' p_c): the penalty energy p_c V_o, where V_o is the volume of
   * space the deformed body covers more than once or a negative number of
   * times,
   *   V_o = int (w(x) - 1)_+ + (-w(x))_+ dx,
   * w the generalized winding number of the deformed boundary (as in
   * solid::tangled_volume_fraction()). This is the volume-contact idea of
   * Allard, Faure, Courtecuisse et al. (2010, "Volume contact constraints
   * at arbitrary resolution", in SOFA) and of Baraff, Witkin and Kass
   * (2003, "Untangling cloth"): it is defined for overlaps that are already
   * there (a crushed or scrambled start, a fold-over of positive elements,
   * which elasticity alone holds in equilibrium), not only for surfaces
   * about to meet, so it can untangle them.
   *
   * Its gradient: w jumps by 1 across a boundary facet, from w_in on the
   * side its reference normal leaves to w_in - 1. Moving a facet of area
   * vector a by delta along its normal turns a layer of volume |a| delta
   * from w_in - 1 to w_in, so dV_o = |a| delta c with
   *   c = phi(w_f + 1/2) - phi(w_f - 1/2),  phi(w) = (w - 1)_+ + (-w)_+,
   * w_f the winding number at the facet's centre of all other facets: a
   * facet of an untangled body (w_f = 1/2) feels nothing; a facet inside
   * the body elsewhere (w_f = 3/2, c = 1) is pushed back into its own part
   * by the pressure p_c; one whose own cell is inverted against the rest
   * (w_f = -1/2, c = -1) is pushed out; c is linear in between.
   *
   * The weights c change only where facets cross each other, and their
   * winding numbers cost (boundary facets)^2 / processes, so they are
   * taken at each step's start (begin_step()) and held over the step. Over
   * the step each facet f then has the energy
   *   E_f = dim p_c c_f V(o_f, x_f),
   * V the signed volume of the simplex spanned by the facet and its
   * centre o_f at the step's start (in 2D a triangle's area): its
   * gradient there is p_c c_f a_f / dim per vertex, the force above shared
   * equally, and it has a Hessian, so that Newton gets the tangent of the
   * facet's turning and stretching, and the line search an energy whose
   * gradient the residual is. (A dead load held over the step, as before,
   * overshoots where the overlap closes within the step.)
   *
   * Straight facets from the vertices (quadrilaterals as two triangles).
   * Every process gathers the boundary facets of the whole mesh at the
   * step's start. Nothing in 1D.
   */
  template <int dim>
  class SelfContact : public forces::Interface<dim>
  {
  public:
    /// 'Boundary conditions/Self contact pressure' and 'Self contact
    /// tangent' (in that subsection, where parameter files have them).
    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * Self contact at the pressure the file gives or, for 'automatic',
     * twice the shear modulus of the stiffest invertible neo-Hookean
     * material on triangles or tetrahedra with an integrator that begins
     * steps (null where that is 0), noting the pressure and why in
     * @p scene's notes.
     */
    static std::unique_ptr<forces::Interface<dim>>
    create(ParameterHandler &prm, const forces::SceneData<dim> &scene);

    /// With the pressure p_c (stress units, > 0); without @p tangent each
    /// facet's force at the step's start is held over the step as a dead
    /// load (energy -f . u, no Jacobian).
    SelfContact(const solid::Discretization<dim> &discretization,
                const double                      pressure,
                const bool                        tangent = true);

    void
    add(const VectorType                &u,
        const double                     time,
        const bool                       jacobian,
        const AffineConstraints<double> &rows,
        const bool                       inhomogeneous,
        MatrixType                      &matrix,
        VectorType                      &residual) const override;

    double
    energy(const VectorType &u, const double time) const override;

    /// Takes each facet's weight c and centre at the ghosted @p u.
    void
    begin_step(const VectorType &u, const double time) override;

  private:
    /// A boundary facet whose weight is not 0: its vertices' dofs (vertex
    /// i, component c at i dim + c), reference positions, weight and
    /// centre at the step's start.
    struct Facet
    {
      std::array<types::global_dof_index, dim * dim> dofs;
      std::array<Point<dim>, dim>                    X;
      double                                         weight;
      Point<dim>                                     centre;
      /// dE_f/du at the step's start (the dead load's minus force).
      std::array<double, dim * dim> start_gradient;
    };

    /// For @p facet at the ghosted @p u: the determinant of its vertices
    /// relative to its centre, with its gradient @p gradient (per vertex
    /// and component) and, if asked, its Hessian @p hessian.
    double
    determinant(const Facet                   &facet,
                const VectorType              &u,
                std::array<double, dim * dim> &gradient,
                FullMatrix<double>            *hessian) const;

    const solid::Discretization<dim>  &discretization;
    double                             pressure;
    bool                               tangent;
    std::vector<Facet>                 facets;
    boost::signals2::scoped_connection mesh_changed;
  };
} // namespace tissuefem::contact
