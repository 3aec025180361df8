#pragma once

#include <deal.II/base/index_set.h>

#include <tissuefem/base/parallel.h>
#include <tissuefem/solid/force_contribution.h>
#include <tissuefem/solid/iteration_unknowns.h>
#include <tissuefem/solvers/linear_solver.h>

#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace tissuefem::solid
{
  using namespace dealii;

  /**
   * The Rayleigh damping force of a state that an integrator reached by a
   * step of size @p step from @p u_old with mass and stiffness factors
   * @p alpha and @p beta (doc/user_guide.md, Rayleigh damping;
   * ImplicitOneStep::damp()): f_d = alpha M v + beta/h (r(u) - r(u_old)),
   * v = (u - u_old)/h, r(u) = f_int(u) - f_ext(t) with the force
   * contributions, both at the state's time: the term the step's equation
   * holds, so that the forces on held and clamped parts balance it.
   * Inactive (alpha = beta = 0) for undamped integrators.
   */
  struct RayleighDamping
  {
    double     alpha = 0, beta = 0, step = 0;
    VectorType u_old;
  };


  /**
   * What a discretized hyperelastic solid offers a time integrator, for
   * the semi-discrete equations of motion
   *
   *   M a + f_int(u) = f_ext(t),   u = g(t) on the Dirichlet boundary,
   *
   * with M the mass matrix (consistent, or lumped by row sums), f_int_a =
   * int P(F) : grad N_a dV and f_ext_a = int (rho_0 g + b) N_a dV + int h
   * N_a dA (problem session eqs 1-2, lecture notes eq 2.11). Every vector
   * is distributed over the processes (locally owned entries); the class
   * makes ghosted copies itself. Independent of the space dimension, so
   * that integrators are written once.
   *
   * Constrained degrees of freedom (Dirichlet components, hanging nodes)
   * are handled here: residuals have zero rows there, Jacobians non-zero
   * diagonals, so that Newton updates obey homogeneous constraints.
   */
  class Operators
  {
  public:
    virtual ~Operators() = default;

    /// A vector laid out like the unknowns (zero).
    virtual void
    initialize_vector(VectorType &v) const = 0;

    virtual types::global_dof_index
    n_dofs() const = 0;
    /// Displacement components per node (the space dimension); a node's
    /// degrees of freedom are consecutive.
    virtual unsigned int
    n_components() const = 0;

    /// The diameter of the reference body (length units): a scale against
    /// which integrators judge displacements.
    virtual double
    length_scale() const = 0;

    /// Sets the constrained entries of @p u: Dirichlet values at @p time,
    /// hanging nodes from their parents.
    virtual void
    apply_dirichlet_values(const double time, VectorType &u) const = 0;

    /// Sets every constrained entry of @p v to zero (for increments).
    virtual void
    zero_constrained_entries(VectorType &v) const = 0;

    /// The initial displacement and velocity of the scene.
    virtual void
    initial_state(VectorType &u, VectorType &v) const = 0;

    /**
     * The residual of one implicit step,
     *   R(u) = c M (u - u_tilde) + f_int(u) - f_ext(t),
     * with the mass of mass_vmult(), and on request its Jacobian c M + K(u)
     * (kept in jacobian()). c = 0 is quasistatics. Throws SolverError
     * (InvertedElementError) for states the model cannot evaluate.
     */
    virtual void
    implicit_residual(const VectorType &u,
                      const VectorType &u_tilde,
                      const double      mass_coefficient,
                      const double      time,
                      VectorType       &residual,
                      const bool        with_jacobian)
      = 0;

    /**
     * For a state @p u whose prescribed entries still hold earlier values:
     * the Jacobian J = c M + K(u) of implicit_residual() and a residual
     * with the Dirichlet increment d = g(time) - u (on the prescribed
     * entries) lifted into it, R(u) + J d on the free rows and -diag d on
     * the prescribed ones, so that the update du solving J du = -R has
     * du = d there and carries the boundary motion into the body linearly
     * (the first iteration of a Newton method with inhomogeneous
     * constraints), instead of a boundary layer of distorted elements.
     *
     * Without @p with_jacobian (a caller that solves with a kept
     * factorization), J may be left as last assembled where the residual
     * can do without it: J d then comes from the matrices of the cells
     * whose prescribed values move, and the prescribed rows take J's kept
     * diagonal. Returns whether J was assembled.
     */
    virtual bool
    implicit_residual_lifting(const VectorType &u,
                              const VectorType &u_tilde,
                              const double      mass_coefficient,
                              const double      time,
                              VectorType       &residual,
                              const bool        with_jacobian)
      = 0;

    /**
     * The potential whose gradient (on the unconstrained entries) is
     * implicit_residual(): c/2 (u - u_tilde)^T M (u - u_tilde) + int Psi dV
     * - f_ext(t) . u (problem session eq 20 for backward Euler, c =
     * 1/dt^2). Used by the energy line search; NaN where there is none.
     */
    virtual double
    implicit_energy(const VectorType &u,
                    const VectorType &u_tilde,
                    const double      mass_coefficient,
                    const double      time)
    {
      (void)u;
      (void)u_tilde;
      (void)mass_coefficient;
      (void)time;
      return std::numeric_limits<double>::quiet_NaN();
    }

    /// The Jacobian of the last implicit_residual() call that asked for it.
    /// Not available after solve_only_through_operators(true) where that
    /// changed the form of the Newton systems.
    virtual MatrixType &
    jacobian()
      = 0;

    /**
     * Declares (with @p only true) that the caller solves the Newton
     * systems with the Jacobian only through solve_jacobian() with
     * @p solver and never asks for jacobian(): then, with a direct solver,
     * a formulation may solve an equivalent system of another form (the
     * nodal dilatation's, nodal_dilatation_system.h). Where that changes
     * the matrix, @p solver is reset first (a kept factorization refers to
     * the matrix).
     */
    virtual void
    solve_only_through_operators(const bool only, solvers::LinearSolver &solver)
    {
      (void)only;
      (void)solver;
    }

    /// Solves J x = b with the Jacobian of the last implicit_residual() or
    /// implicit_residual_lifting() that asked for it (b its negated
    /// residual), as solvers::LinearSolver::solve() does (@p from_guess:
    /// an iterative solver starts from @p x).
    virtual void
    solve_jacobian(solvers::LinearSolver &solver,
                   VectorType            &x,
                   const VectorType      &b,
                   const bool             refactorize,
                   const double           relative_tolerance,
                   const bool             from_guess = false)
    {
      solver.solve(
        jacobian(), x, b, refactorize, relative_tolerance, from_guess);
    }

    /// f_int(u) alone (no matrix): what explicit methods evaluate. Rows of
    /// constrained degrees of freedom are included.
    virtual void
    internal_force(const VectorType &u, VectorType &force)
      = 0;

    /**
     * f_int(u) plus the force contributions' dE/du at (@p u, @p time)
     * (contact with obstacles at their place at that time): what an
     * explicit method that honours contact evaluates.
     */
    virtual void
    internal_force(const VectorType &u, const double time, VectorType &force)
    {
      (void)time;
      internal_force(u, force);
    }

    /**
     * A bound on the squared angular frequency (1 / time^2 units) the force
     * contributions can add to the lumped-mass system in any state: the
     * largest ratio of their stiffness bound (Gershgorin's row sums) to the
     * lumped mass over the free degrees of freedom. An explicit step adds
     * it to the elements' omega_max^2 (the largest eigenvalue of a sum is at
     * most the sum of the largest).
     */
    virtual double
    contribution_frequency_bound()
    {
      return 0;
    }

    /// Wall time spent in the force contributions since the start
    /// (seconds; contact's share of the steps).
    virtual double
    contribution_seconds() const
    {
      return 0;
    }
    /**
     * f_int(u) from the cells flagged in @p active_cells only (indexed as
     * cells_touching() returns them): the others contribute nothing. For
     * active regions (Jeffrey's node freezing), where the skipped cells are
     * those whose nodes all stay put.
     */
    virtual void
    internal_force_on(const VectorType        &u,
                      const std::vector<bool> &active_cells,
                      VectorType              &force)
      = 0;
    /// Flags, per cell of this process's share, whether any of its degrees
    /// of freedom has a non-zero entry in @p mask.
    virtual std::vector<bool>
    cells_touching(const VectorType &mask) = 0;
    /// Sets @p mask to 1 on the degrees of freedom of the cells flagged in
    /// @p cells (indexed as cells_touching() returns them), 0 elsewhere;
    /// collective.
    virtual void
    mark_dofs_of(const std::vector<bool> &cells, VectorType &mask)
      = 0;

    /// f_ext(t) (rows of constrained degrees of freedom included).
    virtual void
    external_force(const double time, VectorType &force)
      = 0;

    /**
     * The force the body exerts on whatever holds its held vertices (a
     * grasping tool; see Solid::hold()), for a state (u, a) at @p time
     * reached with @p damping: minus the sum over the held degrees of
     * freedom of M a + f_int(u) - f_ext(t) + f_d (RayleighDamping); dim
     * components (force units), zero when nothing is held.
     */
    virtual std::vector<double>
    held_force(const VectorType      &u,
               const VectorType      &acceleration,
               double                 time,
               const RayleighDamping &damping)
      = 0;
    /**
     * Groups of degrees of freedom whose Jacobian columns share no row
     * (a distance-2 colouring of the matrix graph), the same on every
     * process: perturbing all of one group at once and differencing the
     * internal force recovers all their columns (Curtis, Powell and Reid's
     * finite-difference Jacobian). Built on first use.
     */
    virtual const std::vector<std::vector<types::global_dof_index>> &
    column_groups()
      = 0;
    /// Whether some degrees of freedom are hanging-node constraints (an
    /// adapted mesh); methods with lumped masses do not support them.
    virtual bool
    has_hanging_nodes() const = 0;

    /**
     * Whether the loads or the prescribed displacements change with time
     * (an expression names t, or a tool moves what it holds). If not, a
     * quasistatic problem is the same at every time: a smaller step cannot
     * help a failed one.
     */
    virtual bool
    changes_with_time() const = 0;

    /// The load factor lambda(@p time) that scales every load
    /// ('Boundary conditions/Load factor', dimensionless), if that factor
    /// names t; none if it is a constant, so that a report does not call
    /// loads whose own expressions name t "load factor 1".
    virtual std::optional<double>
    load_factor(const double time) const = 0;

    /// How the loads (gravity, body force, tractions) vary: there are
    /// none, they are constant in time, or an expression (a load's or the
    /// load factor's) names t.
    enum class LoadHistory
    {
      none,
      constant,
      changing
    };

    virtual LoadHistory
    load_history() const = 0;

    /// lambda(@p time) of 'Load factor', whether or not it names t.
    virtual double
    load_factor_at(const double time) const = 0;

    /**
     * Load continuation: until called again, every load is scaled by
     * @p factor instead of lambda(t) (none: lambda(t) again), in the
     * residual, energy, reactions and error indicators alike. A
     * quasistatic step that failed takes part of its load increment so
     * (time/quasistatic.cc).
     */
    virtual void
    hold_load_factor(const std::optional<double> factor)
      = 0;

    /**
     * Takes the loads that depend on the state (self contact,
     * 'Boundary conditions/Self contact pressure') from @p u at @p time,
     * the start of the implicit step about to be taken: implicit_residual()
     * and implicit_energy() then hold them as dead loads over the step.
     * Force contributions with history (friction) note the step's start.
     */
    virtual void
    begin_step(const VectorType &u, const double time)
    {
      (void)u;
      (void)time;
    }

    /// The implicit step begun last has been accepted at @p u, @p time:
    /// force contributions with history (friction's stick points) commit
    /// it.
    virtual void
    accept_step(const VectorType &u, const double time)
    {
      (void)u;
      (void)time;
    }

    /**
     * After an implicit step's Newton solve has converged at @p u (at
     * @p time, the @p update-th time in this step, from 0): the force
     * contributions with multipliers (an augmented-Lagrangian contact)
     * update them (ForceContribution::augment()). Returns the least
     * settled answer of them: failed before again before satisfied.
     */
    virtual Augmentation
    augment(const VectorType  &u,
            const double       time,
            const unsigned int update,
            std::string       &message)
    {
      (void)u;
      (void)time;
      (void)update;
      (void)message;
      return Augmentation::satisfied;
    }

    /// Unknowns Newton must update alongside u (the three-field mean
    /// dilatation element's cell dilatations and pressures); null if the
    /// operators have none.
    virtual IterationUnknowns *
    iteration_unknowns()
    {
      return nullptr;
    }

    /// The consistent mass matrix, assembled on first use.
    virtual const MatrixType &
    mass_matrix()
      = 0;

    /// @p dst = M @p src with the mass the equations of motion use (the
    /// consistent one, or the lumped one under 'Finite element/Mass =
    /// lumped'), without constraints: the inertial term of
    /// implicit_residual() and its energy.
    virtual void
    mass_vmult(VectorType &dst, const VectorType &src)
      = 0;

    /// The row-sum lumped mass (one entry per degree of freedom).
    virtual const VectorType &
    lumped_mass()
      = 0;

    /// int Psi(F(u)) dV (energy units).
    virtual double
    stored_energy(const VectorType &u) const = 0;

    /// 1/2 v^T M v with the mass of mass_vmult() (energy units).
    virtual double
    kinetic_energy(const VectorType &v)
      = 0;

    /**
     * The force each boundary in @p boundary_ids applies to the body, for
     * a state (u, a) at @p time reached with @p damping: the sum over that
     * boundary's degrees of freedom of M a + f_int(u) - f_ext(t) + f_d
     * (RayleighDamping), without constraints; dim components per boundary,
     * one after the other (force units).
     */
    virtual std::vector<double>
    reaction_forces(const VectorType                      &u,
                    const VectorType                      &acceleration,
                    const double                           time,
                    const RayleighDamping                 &damping,
                    const std::vector<types::boundary_id> &boundary_ids)
      = 0;
  };
} // namespace tissuefem::solid
