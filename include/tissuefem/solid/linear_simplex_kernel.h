#pragma once

#include <deal.II/base/tensor.h>

#include <tissuefem/materials/material_set.h>
#include <tissuefem/solid/cell_cache.h>
#include <tissuefem/solid/discretization.h>
#include <tissuefem/solid/fibre_field.h>

#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace tissuefem::solid
{
  /**
   * The lean element kernel of linear triangles and tetrahedra in the
   * displacement formulation, beside the general quadrature loop of
   * Solid::assemble() (which stays the reference for every other element
   * and for checking this one: tests/unit/lean_kernel.cc).
   *
   * On a P1 simplex F = I + sum_k u_k (x) g_k is constant, so the element
   * force is f_k = V P(F) g_k and the stiffness K_(ka)(lb) = V A_ambn g_km
   * g_ln (problem session eq 19) with V the volume: one stress (and
   * tangent) evaluation per cell instead of one per quadrature point,
   * unless the fibre direction varies within the cell, in which case the
   * fibre material is evaluated at each quadrature point with its weight,
   * as the general path does. The consistent mass of a P1 simplex is
   * rho V (1 + delta_kl) / ((d + 1)(d + 2)) and the gravity load rho g V /
   * (d + 1), in closed form.
   *
   * Per mesh, build() stores for each cell its shape gradients, volume,
   * fibre, density and material, and the local indices of its dofs in the
   * ghosted vectors; cells are ordered into batches of one material, so
   * that the model is called once per batch (materials::Interface::
   * stresses()) and no virtual call or allocation happens per cell.
   * evaluate() computes every cell's element vector into per-cell
   * storage, in parallel (the cells are independent); add_direct() then
   * adds those of cells without constraints into the owned rows of the
   * residual in parallel over rows, each row summing its cells in a fixed
   * order. The element matrices of those cells go straight into the
   * Trilinos matrix as they are computed (Input::matrix_rows), in phases
   * of batches that share no node, the phases one after the other: no
   * two threads write one entry, and each entry sums its cells in phase
   * order. Neither sum depends on the number of threads. Storing the
   * matrices for a gather by rows cost 720 bytes per tetrahedron and, on
   * SOFA's beams, the gather alone a third of the assembly
   * (doc/studies.md). Cells with constrained or non-owned dofs keep their
   * matrices (cell_matrix()) for the caller (AffineConstraints).
   */
  template <int dim>
  class LinearSimplexKernel
  {
  public:
    static constexpr unsigned int n_nodes = dim + 1;
    static constexpr unsigned int n_dofs  = dim * (dim + 1);
    /// A cell matrix is stored as its node blocks k <= l (dim x dim each,
    /// row-major): K is symmetric, and the blocks below the diagonal would
    /// be 40 % more to write and read (3D: 90 entries instead of 144).
    static constexpr unsigned int n_packed
      = n_nodes * (n_nodes + 1) / 2 * dim * dim;

    /// Where block (k, l), k <= l, of a packed cell matrix begins.
    static constexpr unsigned int
    block(const unsigned int k, const unsigned int l)
    {
      return (k * n_nodes - k * (k - 1) / 2 + (l - k)) * dim * dim;
    }

    /// The P1 simplex's mass between nodes k and l, per component (the
    /// same component at both). Consistent: rho V (1 + delta_kl) / ((d +
    /// 1)(d + 2)), the exact integral of two barycentric coordinates over
    /// the simplex; @p lumped, its row sums on the diagonal: delta_kl rho V
    /// / (d + 1). Shared with the nodal dilatation's cell blocks
    /// (NodalDilatationSystem::Loads).
    static constexpr double
    mass(const double rho,
         const double V,
         const bool   same_node,
         const bool   lumped = false)
    {
      if (lumped)
        return same_node ? rho * V / (dim + 1) : 0.;
      return (same_node ? 2. : 1.) * rho * V / ((dim + 1) * (dim + 2));
    }

    /// Its load per node and component under the acceleration @p g:
    /// rho g V / (d + 1).
    static constexpr double
    gravity_load(const double rho, const double V, const double g)
    {
      return rho * g * V / (dim + 1);
    }

    /// Whether the kernel computes what the general path would: linear
    /// simplices in 2D or 3D and a quadrature rule exact for the P1 mass
    /// matrix. (Whether the formulation lets it serve, wholly or for the
    /// inertia and gravity only, Input::internal false, is the
    /// formulation's: formulations::Interface::lean_kernel().)
    static bool
    applies(const Discretization<dim> &discretization,
            const CellCache<dim>      &cache);

    /**
     * Stores the per-cell data for the current mesh. @p ghost_index[c * n +
     * i] is the index in the ghosted vectors of dof i (in local_index
     * order of @p cache) of cached cell c; @p direct[c] whether the cell's
     * element objects may be added in place and @p row[c * n + i] the
     * owned row of its dof i.
     */
    void
    build(const CellCache<dim>              &cache,
          const FibreField<dim>             &fibres,
          const materials::MaterialSet<dim> &materials,
          const std::vector<int>            &ghost_index,
          const std::vector<bool>           &direct,
          const std::vector<int>            &row,
          const unsigned int                 n_owned_rows);

    /// What one evaluation computes (see Solid's Request).
    struct Input
    {
      const double *u = nullptr; ///< ghosted displacement, or null (zero)
      const double *w = nullptr; ///< ghosted inertia vector, or null
      double        mass_jacobian_coefficient = 0;
      /// The mass is the row-sum lumped one ('Finite element/Mass').
      bool           lumped_mass = false;
      Tensor<1, dim> gravity;
      bool           internal = true;
      bool           external = true;
      bool           jacobian = false;
      /// Cells to evaluate (by cache index), all if null.
      const std::vector<bool> *cells = nullptr;
      /// With jacobian: the cells whose matrices are computed (by cache
      /// index; all if null); the others' are left as they were.
      const std::vector<bool> *jacobian_cells = nullptr;
      /// With jacobian: the owned rows' values in the Trilinos matrix, the
      /// owned row of dof i (element order) of cell c at matrix_row_of[c *
      /// n + i], and the position there of its entry j at
      /// matrix_entries[(c * n + i) * n + j]. The direct cells' matrices
      /// are added there; without, they are dropped (only the others' are
      /// kept: cell_matrix()).
      const std::vector<double *>      *matrix_rows    = nullptr;
      const std::vector<int>           *matrix_row_of  = nullptr;
      const std::vector<std::uint16_t> *matrix_entries = nullptr;
    };

    /**
     * Element vectors of every cell, in the kernel's dof order (node k,
     * component a at k * dim + a), and with Input::jacobian their matrices:
     * kept for the cells that are not direct (cell_matrix()), added into
     * Input::matrix_rows for the direct ones (dropped without). Returns the
     * cells (cache index, det F) where det F <= 0 for a model that cannot
     * represent it. With Input::cells and no Jacobian (an active region),
     * only the selected cells are computed, in batches of selected cells,
     * and the others' element vectors are left as they were: add
     * selected() only. With Input::cells and a Jacobian, the others get
     * zeros (and add nothing to the matrix).
     */
    std::vector<std::pair<unsigned int, double>>
    evaluate(const Input &input);

    /// int Psi dV over this process's cells for the ghosted displacement
    /// @p u, one energy evaluation per cell (per point where the fibre
    /// varies), in parallel, summed in cache order; +infinity where a cell
    /// is inverted for a model that cannot represent it.
    double
    stored_energy(const double *u) const;

    /// 1/2 v^T M v over this process's cells for the ghosted velocity @p v,
    /// with the closed-form P1 mass: per cell rho V / ((d + 1)(d + 2)) / 2
    /// (sum_k |v_k|^2 + |sum_k v_k|^2).
    double
    kinetic_energy(const double *v) const;

    /// Adds the element vectors of direct cells into the owned rows
    /// @p residual (their matrices went in with evaluate()).
    void
    add_direct(double *residual) const;

    /// Bytes held (per-cell data, the last evaluation's element vectors
    /// and the kept matrices of the cells that are not direct).
    std::size_t
    memory_consumption() const;

    /// The cells the last evaluation with Input::cells and no Jacobian
    /// computed, in batch order.
    const std::vector<unsigned int> &
    selected() const
    {
      return selection;
    }

    /// The element vector of cached cell @p c, and entry (i, j) of its
    /// matrix (the kernel's dof order; a cell that is not direct).
    const double *
    cell_vector(const unsigned int c) const
    {
      return &vectors[c * n_dofs];
    }
    double
    cell_matrix(const unsigned int c,
                const unsigned int i,
                const unsigned int j) const
    {
      Assert(slot[c] >= 0, ExcInternalError());
      const double      *K = &matrices[slot[c] * n_packed];
      const unsigned int k = i / dim, l = j / dim;
      return k <= l ? K[block(k, l) + (i % dim) * dim + j % dim]
                    : K[block(l, k) + (j % dim) * dim + i % dim];
    }

    /// Whether cached cell @p c keeps its matrix: it is not direct (as
    /// build() was told).
    bool
    keeps_matrix(const unsigned int c) const
    {
      return slot[c] >= 0;
    }

  private:
    /// Cells of one material, evaluated together.
    struct Batch
    {
      unsigned int                     begin, end; ///< into order
      const materials::Interface<dim> *material;
      double                           density;
    };

    /// Whether @p input asks for cached cell @p c's matrix.
    static bool
    wants_matrix(const Input &input, const unsigned int c)
    {
      return input.jacobian
             && (!input.jacobian_cells || (*input.jacobian_cells)[c]);
    }

    /// F = I + sum_k u_k (x) g_k of cached cell @p c, ghosted @p u.
    Tensor<2, dim>
    deformation_gradient(const unsigned int c, const double *u) const;

    /// The sum over batches of @p batch_sum, evaluated in parallel and
    /// added in batch order (the same with any number of threads).
    double
    sum_over_batches(
      const std::function<double(const Batch &)> &batch_sum) const;

    /// Element vector (and matrix) of cached cell @p c from the stresses
    /// (and tangents, or with @p blocks the model's node blocks) of the
    /// batch's work space starting at @p first_point; zeros if @p skipped.
    void
    cell_objects(const unsigned int c,
                 const bool         skipped,
                 const unsigned int first_point,
                 const double       rho,
                 const Input       &input,
                 const bool         blocks);

    /// Adds the packed matrix @p K of direct cell @p c into
    /// Input::matrix_rows.
    void
    scatter(const unsigned int c, const double *K, const Input &input) const;

    /// Colours the batches so that no two of one colour share a node, and
    /// orders them by colour into phase_batches and phase_begin.
    void
    make_phases();

    /// Evaluates the cells of one batch.
    void
    evaluate_batch(const Batch                                  &batch,
                   const std::vector<unsigned int>              &cells,
                   const Input                                  &input,
                   std::vector<std::pair<unsigned int, double>> &inverted);

    /// Fills selection and selection_batches with the cells flagged in
    /// @p cells, batched as batches are (one material, batch_size cells).
    void
    select(const std::vector<bool> &cells);

    materials::TangentMethod method;
    bool                     project = false;
    /// Cache indices in batch order.
    std::vector<unsigned int> order;
    std::vector<Batch>        batches;
    /// The cells of the last active-region evaluation and their batches
    /// (into selection).
    std::vector<unsigned int> selection;
    std::vector<Batch>        selection_batches;
    /// Per cache index: shape gradients [c * n_nodes + k], volume, the
    /// local ghosted index of each dof [c * n_dofs + i] (component-major
    /// per node: node k, component a at k * dim + a).
    std::vector<Tensor<1, dim>> gradients;
    std::vector<double>         volume;
    std::vector<int>            ghost;
    /// Per cache index: the element's dof index of node k, component a.
    std::vector<unsigned int> local_index;
    /// Fibre points: for cell c, points [point_begin[c], point_begin[c +
    /// 1]) with their fibre and weight (the volume if the fibre is uniform
    /// over the cell, else one per quadrature point).
    std::vector<unsigned int>   point_begin;
    std::vector<Tensor<1, dim>> point_fibre;
    std::vector<double>         point_weight;
    /// Owned rows: positions c * n_dofs + i of direct cells' entries
    /// landing there, [row_begin[r], row_begin[r + 1]).
    std::vector<unsigned int> row_begin;
    std::vector<unsigned int> row_positions;
    /// Batches by phase: phase p is phase_batches[phase_begin[p],
    /// phase_begin[p + 1]) (indices into batches).
    std::vector<unsigned int> phase_batches, phase_begin;
    /// Per cache index: where the cell's matrix is kept in matrices (-1 for
    /// a direct cell, whose matrix is not kept).
    std::vector<int>    slot;
    int                 n_kept = 0;
    std::vector<double> vectors, matrices;
    /// The most points of one cell (1, or n_q where a fibre varies).
    unsigned int most_points = 1;
    /// Whether the last evaluation's matrices hold the mass only (no
    /// elastic part: the nodal dilatation's), which couples each component
    /// with itself alone: scatter() then adds a third of the entries (a half
    /// in 2D).
    bool mass_only = false;
  };
} // namespace tissuefem::solid
