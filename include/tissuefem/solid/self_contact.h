#pragma once

#include <deal.II/lac/affine_constraints.h>

#include <tissuefem/base/parallel.h>
#include <tissuefem/solid/discretization.h>

namespace tissuefem::solid
{
  /**
   * Self contact by overlap volume: the force of the penalty energy
   * p_c V_o, where V_o is the volume of space the deformed body covers more
   * than once or a negative number of times,
   *   V_o = int (w(x) - 1)_+ + (-w(x))_+ dx,
   * w the generalized winding number of the deformed boundary (as in
   * tangled_volume_fraction()). This is the volume-contact idea of Allard,
   * Faure, Courtecuisse et al. (2010, "Volume contact constraints at
   * arbitrary resolution", in SOFA) and of Baraff, Witkin and Kass (2003,
   * "Untangling cloth"): it is defined for overlaps that are already there
   * (a crushed or scrambled start, a fold-over of positive elements, which
   * elasticity alone holds in equilibrium), not only for surfaces about to
   * meet, so it can untangle them.
   *
   * Its gradient: w jumps by 1 across a boundary facet, from w_in on the
   * side its reference normal leaves to w_in - 1. Moving a facet by delta
   * along its deformed unit normal n turns a layer of area A delta from
   * w_in - 1 to w_in, so
   *   dV_o = A delta (phi(w_in) - phi(w_in - 1)),  phi(w) = (w - 1)_+ + (-w)_+.
   * With w_f = w_in - 1/2 the winding number at the facet's centre of all
   * other facets: a facet of an untangled body (w_f = 1/2) feels nothing; a
   * facet inside the body elsewhere (w_f = 3/2) is pushed back into its own
   * part by the pressure p_c, f = -p_c A n; one whose own cell is inverted
   * against the rest (w_f = -1/2) is pushed out. Between these values phi
   * is linear, so the force fades in over a winding number of one half.
   *
   * Straight facets from the vertices (quadrilaterals as two triangles);
   * each facet's force goes to its vertices in equal parts. Every process
   * gathers the boundary facets of the whole mesh; the cost is (boundary
   * facets)^2 / processes per call.
   *
   * @p u: ghosted displacement; @p pressure: p_c (Pa if SI); the force is
   * added to @p force, an assembly vector (Discretization::
   * initialize_assembly_vector()), through @p constraints (constrained rows
   * get nothing, hanging-node shares go to their parents); every process
   * calls.
   */
  template <int dim>
  void
  add_overlap_force(const Discretization<dim>       &discretization,
                    const VectorType                &u,
                    const double                     pressure,
                    const AffineConstraints<double> &constraints,
                    VectorType                      &force);
} // namespace tissuefem::solid
