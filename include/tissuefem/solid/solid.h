#pragma once

#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/boundary/boundary_conditions.h>
#include <tissuefem/materials/material_set.h>
#include <tissuefem/solid/cell_cache.h>
#include <tissuefem/solid/change_signals.h>
#include <tissuefem/solid/dilatation_carry.h>
#include <tissuefem/solid/discretization.h>
#include <tissuefem/solid/fibre_field.h>
#include <tissuefem/solid/force_contribution.h>
#include <tissuefem/solid/formulations/interface.h>
#include <tissuefem/solid/linear_simplex_kernel.h>
#include <tissuefem/solid/operators.h>

#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>

namespace tissuefem::solid
{
  /// Thrown when an element inverts (det F <= 0) in a model whose energy is
  /// undefined there; a time integrator may retry with a smaller step.
  class InvertedElementError : public SolverError
  {
  public:
    using SolverError::SolverError;
  };

  /**
   * A hyperelastic solid discretized by finite elements: the Operators an
   * integrator drives, assembled cell by cell over the locally owned cells
   * by several threads (deal.II's WorkStream) and added into distributed
   * Trilinos objects. The per-cell geometry is cached (CellCache), so that
   * repeated assemblies do element arithmetic only.
   *
   * After the mesh changes, call setup() again; every state vector must be
   * transferred by the caller (see adaptation::MeshAdaptation). setup()
   * announces each change through @p signals (ChangeSignals). Hanging-node
   * values of the vectors given to the operators need not be set: the
   * operators compute them from the parents.
   */
  template <int dim>
  class Solid : public Operators, public IterationUnknowns
  {
  public:
    /// With the element @p formulation (formulations::create(); null: the
    /// one 'Materials/Formulation' of @p materials names, with its
    /// default settings).
    Solid(Discretization<dim>                          &discretization,
          const materials::MaterialSet<dim>            &materials,
          boundary::BoundaryConditions<dim>            &boundary_conditions,
          std::unique_ptr<formulations::Interface<dim>> formulation = nullptr);

    /// Distributes dofs, builds constraints, the matrix and the caches for
    /// the current mesh and constraints; after the first time, announces
    /// the change before and after (signals).
    void
    setup();

    /// Announcements of changes of mesh or constraints.
    ChangeSignals signals;

    /**
     * Adds @p contribution (force_contribution.h) to every residual,
     * Jacobian and implicit energy this solid assembles from now on: its
     * dE/du and d2E/du2 wherever the elements' internal forces are
     * assembled, its E in implicit_energy().
     */
    void
    add_force_contribution(std::shared_ptr<ForceContribution<dim>> contribution)
    {
      contributions.push_back(std::move(contribution));
    }

    void
    initialize_vector(VectorType &v) const override;

    unsigned int
    n_components() const override
    {
      return dim;
    }

    types::global_dof_index
    n_dofs() const override
    {
      return discretization.n_dofs();
    }

    double
    length_scale() const override;

    void
    apply_dirichlet_values(const double time, VectorType &u) const override;

    void
    zero_constrained_entries(VectorType &v) const override;

    void
    initial_state(VectorType &u, VectorType &v) const override;

    void
    implicit_residual(const VectorType &u,
                      const VectorType &u_tilde,
                      const double      mass_coefficient,
                      const double      time,
                      VectorType       &residual,
                      const bool        with_jacobian) override;

    bool
    implicit_residual_lifting(const VectorType &u,
                              const VectorType &u_tilde,
                              const double      mass_coefficient,
                              const double      time,
                              VectorType       &residual,
                              const bool        with_jacobian) override;

    double
    implicit_energy(const VectorType &u,
                    const VectorType &u_tilde,
                    const double      mass_coefficient,
                    const double      time) override;

    MatrixType &
    jacobian() override;

    void
    solve_only_through_operators(const bool             only,
                                 solvers::LinearSolver &solver) override;

    void
    solve_jacobian(solvers::LinearSolver &solver,
                   VectorType            &x,
                   const VectorType      &b,
                   const bool             refactorize,
                   const double           relative_tolerance,
                   const bool             from_guess = false) override;

    /// The elements' f_int(u) (no force contributions).
    void
    internal_force(const VectorType &u, VectorType &force) override;

    void
    internal_force(const VectorType &u,
                   const double      time,
                   VectorType       &force) override;

    double
    contribution_frequency_bound() override;

    double
    contribution_seconds() const override
    {
      return contribution_time;
    }

    void
    internal_force_on(const VectorType        &u,
                      const std::vector<bool> &active_cells,
                      VectorType              &force) override;

    std::vector<bool>
    cells_touching(const VectorType &mask) override;

    void
    mark_dofs_of(const std::vector<bool> &cells, VectorType &mask) override;

    void
    external_force(const double time, VectorType &force) override;

    const MatrixType &
    mass_matrix() override;

    const VectorType &
    lumped_mass() override;

    void
    mass_vmult(VectorType &dst, const VectorType &src) override;

    const std::vector<std::vector<types::global_dof_index>> &
    column_groups() override;

    std::vector<double>
    held_force(const VectorType      &u,
               const VectorType      &acceleration,
               double                 time,
               const RayleighDamping &damping) override;

    /**
     * Holds the listed triangulation vertices from now on: all their
     * displacement components follow u_start + motion(t), u_start their
     * displacement in @p u. Rebuilds the constraints through setup(), which
     * announces the change on 'signals' (the caller tells nobody else).
     */
    void
    hold(const std::vector<unsigned int>                   &vertices,
         const std::function<Tensor<1, dim>(const double)> &motion,
         const VectorType                                  &u);

    /// Lets the held vertices go (they keep their state); as hold().
    void
    release();

    bool
    has_hanging_nodes() const override;
    bool
    changes_with_time() const override;
    std::optional<double>
    load_factor(const double time) const override;
    double
    load_factor_at(const double time) const override;
    LoadHistory
    load_history() const override;
    void
    hold_load_factor(const std::optional<double> factor) override;

    double
    stored_energy(const VectorType &u) const override;

    /// What this process holds of the solid, by part (name, bytes): the
    /// mesh (every process holds all of it), the dof numbering with its
    /// constraints, assembly's per-cell caches, the Jacobian and the mass
    /// matrix; not vectors, nor a linear solver's factors or hierarchy.
    std::vector<std::pair<std::string, std::size_t>>
    memory_parts() const;

    double
    kinetic_energy(const VectorType &v) override;

    std::vector<double>
    reaction_forces(
      const VectorType                      &u,
      const VectorType                      &acceleration,
      const double                           time,
      const RayleighDamping                 &damping,
      const std::vector<types::boundary_id> &boundary_ids) override;

    const Discretization<dim> &
    get_discretization() const
    {
      return discretization;
    }

    const materials::MaterialSet<dim> &
    get_materials() const
    {
      return materials;
    }

    const boundary::BoundaryConditions<dim> &
    get_boundary_conditions() const
    {
      return boundary_conditions;
    }

    /// Whether assembly uses the lean kernel of linear simplices on this
    /// mesh ('Finite element/Element kernel').
    bool
    lean_kernel_active() const
    {
      return lean != nullptr;
    }

    const FibreField<dim> &
    fibres() const
    {
      return fibre_field;
    }

    /// The element formulation ('Materials/Formulation').
    const formulations::Interface<dim> &
    formulation() const
    {
      return *element;
    }

    /// The formulation's effective deformation gradients of the ghosted
    /// state @p u (outputs: J, stresses).
    std::unique_ptr<formulations::Deformation<dim>>
    deformation(const VectorType &u) const
    {
      return element->deformation(context(), u, nullptr);
    }

    /// The cell dilatations carried across mesh changes, where the
    /// formulation carries them (mean dilatation; see dilatation_carry.h;
    /// else null), which a mesh adaptation records and finishes. They
    /// enter the implicit operators (implicit_residual,
    /// implicit_residual_lifting, implicit_energy) only: outputs and the
    /// other operators see the material as it is.
    DilatationCarry<dim> *
    dilatation_carry()
    {
      return element->carry();
    }

    /// Tells the force contributions that an attempt at a step starts from
    /// @p u at @p time.
    void
    begin_step(const VectorType &u, const double time) override;

    void
    accept_step(const VectorType &u, const double time) override;

    Augmentation
    augment(const VectorType  &u,
            const double       time,
            const unsigned int update,
            std::string       &message) override;

    /// The formulation's own unknowns where it has them (the three-field
    /// form of the mean dilatation element, ThreeFieldDilatation), which
    /// these members drive.
    IterationUnknowns *
    iteration_unknowns() override;
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
      const IterationUnknowns *unknowns = element->iteration_unknowns();
      return unknowns && unknowns->iterating();
    }

  private:
    /// What one assembly pass computes.
    struct Request
    {
      const VectorType                *u       = nullptr; ///< ghosted
      const VectorType                *inertia = nullptr; ///< ghosted w in M w
      double                           mass_jacobian_coefficient = 0;
      double                           time                      = 0;
      bool                             internal                  = true;
      bool                             external                  = true;
      bool                             jacobian                  = false;
      const AffineConstraints<double> *rows                      = nullptr;
      /// Whether the inhomogeneities of @p rows enter the residual.
      bool inhomogeneous = false;
      /// Cells to assemble (all if null), by cache index.
      const std::vector<bool> *cells = nullptr;
      /// Whether the carried cell dilatations apply (implicit requests).
      bool carry = false;
      /// Whether the force contributions (contact) enter with internal
      /// forces, at @p time.
      bool contributions = true;
    };

    /// The reference body's diameter (length_scale()), set by setup().
    double diameter = 0;

    /// Fills dirichlet_points for the current mesh.
    void
    find_dirichlet_points();

    /// Calls @p visit(dof, owned index or -1, value) for every Dirichlet
    /// dof at @p time, in the order in which later conditions override
    /// earlier ones (held vertices last); the owned index is -1 for dofs
    /// not owned here and for hanging nodes.
    template <typename Visitor>
    void
    visit_dirichlet_values(const double time, const Visitor &visit) const;

    /// The prescribed displacement of every Dirichlet dof at @p time.
    std::map<types::global_dof_index, double>
    dirichlet_values(const double time) const;

    /// A request for the implicit-step residual: ghosted u, and the
    /// inertial vector w = c (u - u_tilde) when c != 0.
    Request
    implicit_request(const VectorType &u,
                     const VectorType &u_tilde,
                     const double      mass_coefficient,
                     const double      time);

    /// @p ghosted = @p u with hanging-node values set from their parents.
    void
    make_ghosted(const VectorType &u, VectorType &ghosted) const;

    /// residual = [internal] f_int(u) + [inertia] M w - [external]
    /// f_ext(t), and with jacobian K(u) + c M into jacobian_matrix.
    void
    assemble(const Request &request, VectorType &residual);

    /// assemble() by the lean kernel of linear simplices, for requests it
    /// covers (see uses_lean_kernel()).
    void
    assemble_lean(const Request &request, VectorType &residual);

    /// By cache index: the cells with a dof that @p rows constrains
    /// inhomogeneously (a prescribed value that moves), for the lean
    /// kernel's lifting without the Jacobian.
    std::vector<bool>
    moving_cells(const AffineConstraints<double> &rows) const;

    /// Whether @p request is for the lean kernel: one is built for this
    /// mesh and the request's loads are its (gravity, inertia; no body
    /// force expression or traction).
    bool
    uses_lean_kernel(const Request &request) const;

    /// Before a Jacobian's assembly: the Jacobian laid out with the
    /// formulation's wide couplings where it needs them and keeps no
    /// system of its own, or its own system cleared.
    void
    prepare_jacobian();

    /// The formulation's terms that couple patches of cells (after the
    /// cell loop) for @p request, appending undefined cells to
    /// @p inverted; with @p loads (the lean path's Jacobians into the
    /// formulation's own system) the request's inertia and gravity too.
    void
    add_patch_terms(const Request               &request,
                    VectorType                  &residual,
                    formulations::Inverted<dim> &inverted,
                    const bool                   loads = false);

    /// What the formulation sees of this solid.
    formulations::Context<dim>
    context() const
    {
      return {discretization, materials, cache, fibre_field};
    }

    /// Throws InvertedElementError naming the @p inverted cells (active
    /// cell index, det F, centre), gathered from every process.
    void
    report_inversions(
      const std::vector<std::tuple<unsigned int, double, Point<dim>>> &inverted)
      const;

    /// The stored energy of the ghosted displacement @p ghosted (as
    /// make_ghosted() sets it), with the carried cell dilatations of
    /// @p time where @p carry_time is given (implicit_energy()).
    double
    stored_energy_with(const VectorType &ghosted,
                       const double     *carry_time) const;

    /// The pieces of assemble()'s cell worker (solid_assembly.cc), in the
    /// order it calls them.
    /// Resets @p copy for cache cell @p c and gathers its displacement and
    /// inertia coefficients into @p s.
    template <typename ScratchType, typename CopyType>
    void
    start_cell(const Request     &request,
               const unsigned int c,
               ScratchType       &s,
               CopyType          &copy) const;

    /// Adds, point by point, the elastic terms (if @p elastic) of the
    /// stress and tangent the formulation gave in s.cell (P, A), the
    /// loads and the inertia (density @p rho).
    template <typename ScratchType, typename CopyType>
    void
    add_point_terms(const Request     &request,
                    const unsigned int c,
                    const double       rho,
                    const bool         elastic,
                    ScratchType       &s,
                    CopyType          &copy) const;

    /// The Neumann tractions on the cell's boundary faces.
    template <typename ScratchType, typename CopyType>
    void
    add_tractions(const unsigned int c, ScratchType &s, CopyType &copy) const;

    /// Adds a cell's rows to the residual (and Jacobian): in place where
    /// no constraint touches them, else through the request's rows.
    template <typename CopyType>
    void
    add_to_global(const Request  &request,
                  const CopyType &copy,
                  VectorType     &residual);

    Discretization<dim>               &discretization;
    const materials::MaterialSet<dim> &materials;
    boundary::BoundaryConditions<dim> &boundary_conditions;
    CellCache<dim>                     cache;
    /// The lean kernel, where it applies to the mesh (else null).
    std::unique_ptr<LinearSimplexKernel<dim>> lean;
    /// The element formulation (a registered formulations::Interface).
    std::unique_ptr<formulations::Interface<dim>> element;
    /// Whether the caller solves only through solve_jacobian(), with a
    /// direct solver (solve_only_through_operators()).
    bool                      solves_only_through_operators = false;
    FibreField<dim>           fibre_field;
    AffineConstraints<double> no_constraints;
    /// Constraints with the Dirichlet increment (implicit_residual_lifting).
    AffineConstraints<double>                         lifting_constraints;
    MatrixType                                        jacobian_matrix;
    std::optional<MatrixType>                         mass;
    std::optional<VectorType>                         lumped;
    std::vector<std::vector<types::global_dof_index>> groups;
    /**
     * What a tool holds, between hold() and release(): every displacement
     * component of each vertex is prescribed, u = u_start + motion(t),
     * with u_start its displacement when grasped. The tool chooses the
     * vertices and owns the motion; the solid enforces them as constraints
     * while they are held (they are not part of the user's boundary
     * conditions).
     */
    struct Held
    {
      std::vector<unsigned int>                   vertices;
      std::function<Tensor<1, dim>(const double)> motion;
    };
    std::optional<Held> held;
    /// (dof, vertex, component) of the held vertices, locally relevant,
    /// and their displacement when grasped.
    std::vector<std::tuple<types::global_dof_index, unsigned int, unsigned int>>
                                              held_dofs;
    std::map<types::global_dof_index, double> held_start;
    /// Per Dirichlet condition (in order): each constrained dof with the
    /// support point and component its value is taken at, found once per
    /// mesh, so that the values at a time cost one expression evaluation
    /// per dof instead of a pass over the boundary.
    struct DirichletPoint
    {
      types::global_dof_index dof;
      Point<dim>              point;
      unsigned int            component;
      /// Index among this process's owned entries; -1 if the dof is not
      /// owned here or is a hanging node (whose value comes from others).
      int local = -1;
      /// The value, for conditions that do not depend on time.
      double value = 0;
    };
    std::vector<std::vector<DirichletPoint>> dirichlet_points;

    /// M a + f_int(u) - f_ext(t) + f_d on every row, without constraints.
    void
         unconstrained_residual(const VectorType      &u,
                                const VectorType      &acceleration,
                                const double           time,
                                const RayleighDamping &damping,
                                VectorType            &residual);
    bool body_force_present;
    /// Ghosted copies of the arguments, reused between calls.
    VectorType ghosted_u, ghosted_w;
    /// Forces that do not come from the elements (add_force_contribution).
    std::vector<std::shared_ptr<ForceContribution<dim>>> contributions;
    /// Wall time spent in them so far (contribution_seconds()).
    double contribution_time = 0;

    /// Adds the contributions' terms of an assembly that asks for internal
    /// forces, before the caller compresses.
    void
    add_contributions(const Request &request, VectorType &residual);

    /**
     * Direct access, computed once per mesh: for each cached cell, the
     * local index of each of its dofs in the ghosted vectors (gathers
     * without global-to-local look-ups); and for cells whose dofs this
     * process owns and which carry no constraint, where each element entry
     * goes in the rows of the Trilinos matrix and residual, so that the
     * copy into the global objects bypasses AffineConstraints and Epetra's
     * index searches. Other cells take the general path.
     */
    struct DirectAccess
    {
      std::vector<int>  ghost_index; ///< [c * n + i]
      std::vector<bool> direct;      ///< [c]
      /// [c * n + i], local row of an owned dof (constrained or not),
      /// -1 for others
      std::vector<int> row;
      /// [c * n * n + i * n + j], the entry's position in its row (a
      /// cell with a row of 2^16 entries or more is not direct).
      std::vector<std::uint16_t> entry;
      /// The cached cells having ghosted entry g among their dofs:
      /// cells_of[cells_of_begin[g]] to cells_of[cells_of_begin[g + 1]].
      std::vector<unsigned int> cells_of_begin, cells_of;
      std::vector<double *>     row_values; ///< [local row]
    } access;

    void
    build_direct_access();

    /// The Jacobian's sparsity and matrix for the current dofs (and the
    /// nodal dilatation's system where it serves), then direct access.
    /// The couplings of a formulation's patches only with @p wide:
    /// assemble() asks for them when it first needs them, so that runs
    /// solving through the formulation's own system never build them.
    void
    build_jacobian_matrix(const bool wide);
    /// Whether jacobian_matrix has the patches' wide couplings.
    bool wide_layout = false;

    /**
     * The last state stored_energy() evaluated (its owned values) and the
     * answer, forgotten when the mesh changes. Steps ask for the energy of
     * one state twice: the linearly implicit Euler's check of its new
     * state, then the statistics (on SOFA's corotational beams each costs
     * a polar decomposition per cell, 7 % of the run).
     */
    struct EnergyMemo
    {
      std::vector<double> u;
      double              energy = 0;
      bool                valid  = false;
      std::mutex          lock;
    };
    mutable EnergyMemo energy_memo;
  };
} // namespace tissuefem::solid
