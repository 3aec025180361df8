#pragma once

#include <deal.II/base/quadrature.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/cell_id.h>
#include <deal.II/lac/vector.h>

#include <map>
#include <utility>
#include <vector>

namespace tissuefem::solid
{
  using namespace dealii;

  /**
   * The cell dilatations of the mean dilatation (F-bar) element carried
   * across a mesh change, and released over the steps that follow.
   *
   * Why: with F-bar only the cell mean theta of J is constrained, so J
   * varies freely inside a cell. When the cell is refined, each child's
   * own mean differs from the parent's, and a nearly incompressible
   * material turns the difference into pressure jumps of bulk modulus
   * times it (lambda = 4e5 times 0.05 on Cook's membrane at nu = 0.4999):
   * the interpolated state is far from equilibrium, the huge pressures
   * make the tangent indefinite, and Newton takes dozens of damped
   * iterations or fails. Halving the step does not help, since the
   * imbalance does not scale with the load increment.
   *
   * So each new cell starts with the dilatation of the cell it came from:
   * the solid uses theta_eff = r^w theta in Fbar = (theta_eff / J)^(1/d) F,
   * with r = (carried dilatation) / (the new cell's own theta at the
   * interpolated state). At w = 1 every point of a refined cell sees the
   * Fbar of its parent, so the stress field is the old mesh's and the
   * state as balanced as before. w falls linearly from 1 at the change to
   * 0 after the release duration: the end of a time step of that length
   * faces the whole change, a halved step half of it, so that the
   * integrator's step control becomes a continuation on the mismatch.
   * Coarsened cells carry the volume-weighted mean of their children's
   * (their own theta up to quadrature), unchanged cells what they carried
   * still (a new change restarts the release).
   *
   * With the three-field update (ThreeFieldDilatation, the default) the
   * carried dilatation is instead the first iterate of the cell
   * dilatation unknowns in the step after the change: Newton solves the
   * new mesh's equations at once and, once a step has converged, the
   * carry is cleared (Solid::end_iterations()).
   *
   * Works on meshes every process holds whole (the displacement given is
   * replicated), so that the owner of a child need not own its parent.
   */
  template <int dim>
  class DilatationCarry
  {
  public:
    /// Before the mesh changes (refine and coarsen flags set, the state on
    /// the old mesh): the dilatation each cell will hand on, at @p time.
    void
    record(const DoFHandler<dim> &dof_handler,
           const Mapping<dim>    &mapping,
           const Quadrature<dim> &quadrature,
           const Vector<double>  &u,
           const double           time);

    /// After the change (the state interpolated to the new mesh): the
    /// ratios r of every active cell, released over @p duration (> 0)
    /// from @p time; a cell record() said nothing about carries nothing.
    void
    finish(const DoFHandler<dim> &dof_handler,
           const Mapping<dim>    &mapping,
           const Quadrature<dim> &quadrature,
           const Vector<double>  &u,
           const double           time,
           const double           duration);

    /// The factor r^w by which the active cell @p cell_index scales its
    /// dilatation at @p time (1 where nothing is carried).
    double
    factor(const unsigned int cell_index, const double time) const;

    /// Drops whatever is carried.
    void
    clear();

    /// How many time steps a carried dilatation is released over, as the
    /// formulation reads it ('Materials/Mean dilatation/Release steps';
    /// 0: nothing is carried).
    double release_steps = 1;

    /// The mean dilatation theta = int J dV / V and the volume V of every
    /// active cell (0, 0 for artificial cells) for the whole displacement
    /// vector @p u.
    static std::vector<std::pair<double, double>>
    cell_dilatations(const DoFHandler<dim> &dof_handler,
                     const Mapping<dim>    &mapping,
                     const Quadrature<dim> &quadrature,
                     const Vector<double>  &u);

  private:
    /// Dilatations to hand on: of unchanged and refined cells by their own
    /// id (children look up their parent's).
    std::map<CellId, double> carried;
    /// Of cells to be coarsened, by their parent's id: the sums of V
    /// theta and of V over the children.
    std::map<CellId, std::pair<double, double>> merged;
    /// log r per active cell, and the release's start and duration.
    std::vector<double> log_ratio;
    double              start    = 0;
    double              duration = 0;
  };
} // namespace tissuefem::solid
