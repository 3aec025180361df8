#pragma once

#include <deal.II/base/tensor.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/base/parallel.h>
#include <tissuefem/materials/material_set.h>
#include <tissuefem/solid/discretization.h>
#include <tissuefem/solid/fibre_field.h>
#include <tissuefem/solid/mean_dilatation.h>

#include <array>
#include <map>
#include <mutex>
#include <tuple>
#include <vector>

namespace tissuefem::solid
{
  /**
   * The locking-free linear simplex: F-bar with a nodally averaged
   * dilatation (the average nodal pressure element of Bonet and Burton
   * 1998, as an F-bar patch in the manner of de Souza Neto et al. 2005).
   * On P1 triangles and tetrahedra F, J = det F are constant per cell; at
   * each vertex b the dilatation is the volume-weighted mean over the
   * cells around it, J_b = sum_g V_g J_g / sum_g V_g, and a cell's
   * dilatation is the mean of its vertices', Jbar_e = sum_b J_b / (d + 1).
   * The energy is W = sum_e V_e Psi(Fbar_e), Fbar_e = (Jbar_e / J_e)^(1/d)
   * F_e: the volume change is averaged over the patch of cells around each
   * vertex, which leaves about one volume constraint per vertex instead of
   * one per cell, and so removes the volumetric locking of nearly
   * incompressible materials (nu -> 1/2), with any energy model.
   *
   * Jbar_e depends on every cell that shares a vertex with e, so the
   * residual couples a cell to that patch and the exact Newton tangent to
   * the patches of the patch (add_sparsity()). In parallel the patch of a
   * locally owned cell consists of owned and ghost cells, whose degrees
   * of freedom are locally relevant: no more ghosts are needed.
   */
  template <int dim>
  class NodalDilatation
  {
  public:
    /// Collects the cells of the current mesh this process needs (the
    /// owned ones and those sharing a vertex with them).
    explicit NodalDilatation(const Discretization<dim> &discretization);

    /// Adds the couplings of every owned cell's patch to @p sparsity.
    void
    add_sparsity(const AffineConstraints<double>   &constraints,
                 TrilinosWrappers::SparsityPattern &sparsity) const;

    /// Jbar per active cell index (owned cells; NaN elsewhere), for the
    /// ghosted displacement @p u.
    std::vector<double>
    dilatations(const VectorType &u) const;

    /**
     * Adds the elastic part of the residual, dW/du, and with @p jacobian
     * its exact derivative, for the ghosted displacement @p u, through
     * @p rows (as the cell assembly does). Cells where Fbar is not
     * defined (J or Jbar <= 0), or the model is undefined, contribute
     * nothing and are returned as (active cell index, det F, centre).
     */
    std::vector<std::tuple<unsigned int, double, Point<dim>>>
    assemble(const VectorType                  &u,
             const materials::MaterialSet<dim> &materials,
             const FibreField<dim>             &fibres,
             const bool                         jacobian,
             const AffineConstraints<double>   &rows,
             const bool                         inhomogeneous,
             MatrixType                        &matrix,
             VectorType                        &residual) const;

  private:
    /// Assembles the same tangent in a sparser form from the cells.
    template <int>
    friend class NodalDilatationSystem;
    /// Uses the cells alone.
    template <int>
    friend class NodalPressure;

    struct Cell
    {
      unsigned int                         active_index;
      types::material_id                   material_id;
      double                               volume;
      Point<dim>                           centre;
      std::array<Tensor<1, dim>, dim + 1>  gradient; // of the hat functions
      std::array<unsigned int, dim + 1>    vertex;   // global vertex indices
      std::vector<types::global_dof_index> dofs;
      std::vector<std::pair<unsigned, unsigned>> node_component; // per dof
      bool                                       owned;
    };

    /// F of a cell for the ghosted displacement @p u.
    Tensor<2, dim>
    deformation_gradient(const Cell &cell, const VectorType &u) const;

    /// sum_g V_g J_g over the cells around each vertex (by the
    /// triangulation's vertex index), for the cells' @p J (as cells).
    std::vector<double>
    volume_times_J(const std::vector<double> &J) const;

    /// Jbar of an owned @p cell, sum_{b in cell} J_b / (d + 1) with J_b =
    /// sum_g V_g J_g / V_b from volume_times_J(): the patch's average in
    /// O(1) per cell.
    double
    vertex_average(const Cell &cell, const std::vector<double> &sums) const;

    /**
     * The patch of an owned cell e, fixed per mesh: the cells g sharing a
     * vertex with e, with c_g = dJbar_e/dJ_g = sum over the vertices b that
     * e and g share of V_g / ((d + 1) V_b), V_b the volume around b; the
     * patch's degrees of freedom (sorted); and where each member's and
     * e's own degrees of freedom are among them.
     */
    struct Patch
    {
      unsigned int                           cell;
      std::vector<unsigned int>              members;
      std::vector<double>                    weights;
      std::vector<types::global_dof_index>   dofs;
      std::vector<std::vector<unsigned int>> member_positions;
      std::vector<unsigned int>              own_positions;
    };

    /// The patches of the owned cells, built on the first call.
    const std::vector<Patch> &
    patch_list() const;

    /// Fills patches from the cells around each vertex (around).
    void
    build_patches() const;

    /// Psi-hat = Psi(Fbar) of a cell and its derivatives in (F, theta),
    /// times the cell's volume.
    MeanDilatationPoint<dim>
    derivatives(const Cell                        &cell,
                const Tensor<2, dim>              &F,
                const double                       theta,
                const materials::MaterialSet<dim> &materials,
                const FibreField<dim>             &fibres,
                const bool                         jacobian) const;

    /// The exact tangent of one patch's energy into @p K.
    void
    add_tangent(const Patch                       &patch,
                const Cell                        &cell,
                const MeanDilatationPoint<dim>    &psi,
                const std::vector<double>         &J,
                const std::vector<Tensor<2, dim>> &cofactor,
                const Vector<double>              &w,
                FullMatrix<double>                &K) const;

    /// Jbar_e = sum_g c_g J_g of a patch, for the cells' J.
    double
    dilatation(const Patch &patch, const std::vector<double> &J) const;

    std::vector<Cell> cells;
    /// The cells (indices into cells) around each vertex of an owned cell.
    std::map<unsigned int, std::vector<unsigned int>> around;
    mutable std::vector<Patch>                        patches;
    mutable bool                                      patches_built = false;
    mutable std::mutex                                patch_mutex;
    /// Reference quadrature weights, normalized to sum 1, for the fibre
    /// directions at the points (F is constant per cell).
    std::vector<double> weights;
    /// Of the mesh: the size of dilatations()' result, and its vertices.
    unsigned int n_active_cells = 0, n_vertices = 0;
    /// The volume of the cells around each vertex of an owned cell (0 at
    /// the others), by the triangulation's vertex index.
    std::vector<double> volume_around;
  };
} // namespace tissuefem::solid
