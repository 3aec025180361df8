#pragma once

#include <deal.II/base/parameter_handler.h>

#include <tissuefem/base/parallel.h>
#include <tissuefem/base/registry.h>
#include <tissuefem/solid/operators.h>
#include <tissuefem/solvers/linear_solver.h>
#include <tissuefem/solvers/newton.h>

#include <string>
#include <vector>

namespace tissuefem::time
{
  using namespace dealii;

  /// The 'Time integration' subsection (what every integrator reads).
  struct TimeParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    std::string  integrator;
    double       end_time;
    double       time_step;
    unsigned int max_step_halvings;
    /// Whether implicit one-step methods start Newton from an extrapolation
    /// of the previous steps (else from the previous state).
    bool extrapolate;
    /// Newton iterations per step the step controller aims at; 0: steps
    /// grow back after failures only.
    unsigned int optimal_iterations;
    /// Wall-clock seconds a step may take in an interactive loop.
    double real_time_budget;
    /// Rayleigh damping D = alpha M + beta K ('Rayleigh mass damping',
    /// 1/time units; 'Rayleigh stiffness damping', time units); 0: none.
    double rayleigh_mass      = 0;
    double rayleigh_stiffness = 0;
  };

  /// The state of the body at one instant: displacement, velocity and
  /// acceleration (distributed vectors), at time t.
  struct State
  {
    double     time = 0;
    VectorType u, v, a;
    /// The damping force's terms of the step that reached this state
    /// (inactive for undamped integrators), for the forces on held and
    /// clamped parts.
    solid::RayleighDamping damping;
  };

  /// What one step did, for statistics.csv and the screen.
  struct StepReport
  {
    double       dt                = 0;
    unsigned int newton_iterations = 0;
    unsigned int linear_iterations = 0;
    /// Attempts thrown away (step halvings, rejected error estimates).
    unsigned int rejected_attempts = 0;
    /// l2 norm of the final nodal residual (force units); 0 for explicit
    /// methods.
    double residual_norm    = 0;
    double assembly_seconds = 0;
    double solve_seconds    = 0;
    /// Wall time of the whole step (set by the caller of advance()).
    double step_seconds = 0;
    /// Steps of the integrator's own (adaptive) step size taken within
    /// this call (1 for fixed-step methods).
    unsigned int substeps = 1;
    /// Jacobians evaluated (assembled or differenced) in this call.
    unsigned int jacobian_evaluations = 0;
    /// Re-solves of the step for contact multipliers that moved (the
    /// augmented Lagrangian's Uzawa updates, Operators::augment()).
    unsigned int multiplier_updates = 0;
    /// Wall time spent in the force contributions (contact: detection,
    /// assembly, energies, multiplier updates) in this call (seconds; set
    /// by the caller of advance()).
    double contact_seconds = 0;
    /// Energy taken out by the integrator's damping force in this call
    /// (energy units; 0 without damping).
    double damping_work = 0;
    /// Stored (int Psi dV) and kinetic (1/2 v.M v, Operators::kinetic_energy)
    /// energy of the state reached (set by the caller of advance()).
    double stored_energy  = 0;
    double kinetic_energy = 0;
  };

  /// What an integrator works with: the solid's operators and the solvers.
  struct Context
  {
    solid::Operators                &solid;
    const TimeParameters            &time;
    const solvers::NewtonParameters &newton;
    solvers::LinearSolver           &linear_solver;
  };

  /**
   * A time integrator owns the step: from the state at t it chooses a step
   * h (at most up to @p end_time), computes the state at t + h by driving
   * the solid's operators (residuals and Jacobians for implicit methods,
   * internal forces and lumped masses for explicit ones), and returns what
   * it did. Nothing outside the integrator knows how it steps.
   */
  class Interface
  {
  public:
    virtual ~Interface() = default;

    /// Called once before the first step, with the initial state (u, v set
    /// and satisfying the boundary conditions at its time); may set a.
    virtual void
    initialize(Context &context, State &state)
      = 0;

    /// Advances @p state by one step, not beyond @p end_time. Throws
    /// SolverError when it cannot.
    virtual StepReport
    advance(State &state, const double end_time)
      = 0;

    /// Vectors the integrator keeps besides the state (older steps), which
    /// must be transferred when the mesh changes.
    virtual std::vector<VectorType *>
    history()
    {
      return {};
    }

    /// Called after the mesh changed and the state and history() were
    /// transferred: drop whatever depended on the old mesh.
    virtual void
    mesh_changed()
    {
    }

    /**
     * Checkpoints ('Output/Checkpoint interval'): whether the integrator
     * can be stopped and continued bit-identically from the state, its
     * history() vectors and the numbers checkpoint_scalars() returns
     * (step-size controllers, energy records), which restore_scalars()
     * puts back after initialize() on the restored state.
     */
    virtual bool
    checkpointable() const
    {
      return false;
    }

    virtual std::vector<double>
    checkpoint_scalars() const
    {
      return {};
    }

    virtual void
    restore_scalars(const std::vector<double> &scalars)
    {
      (void)scalars;
    }

    /**
     * What the integrator can be given besides elastic forces and fixed
     * loads. The scene and the run refuse what it cannot take before the
     * first step, naming the parameter, instead of comparing integrator
     * names; an integrator that adds a capability says so here alone.
     */
    struct Capabilities
    {
      /// Whether it integrates in time (false: a sequence of equilibria,
      /// whose loads ramp by default and which needs every part held).
      bool in_time = true;
      /// Whether it begins each step through Operators::begin_step()
      /// (where self contact takes its weights) and passes the time of
      /// each force evaluation (which a moving obstacle needs).
      bool begins_steps = false;
      /// Whether it takes contact with obstacles as a penalty force of
      /// (u, t).
      bool penalty_contact = false;
      /// Whether it re-solves a step for contact multipliers that moved
      /// (Operators::augment(): the augmented Lagrangian).
      bool augmented_lagrangian = false;
      /// Whether it applies 'Rayleigh mass damping' and 'Rayleigh
      /// stiffness damping'.
      bool rayleigh_damping = false;
      /// The parameter whose setting needs every process to hold the
      /// whole mesh (a numerically differenced Jacobian colours the
      /// unknowns of the whole mesh: Solid::column_groups()), or empty.
      std::string whole_mesh_parameter;
      /// What the settings given take away of penalty contact, which the
      /// integrator's defaults take, for messages; empty if nothing.
      std::string taken_away;
    };

    virtual Capabilities
    capabilities() const
    {
      return {};
    }

    /// What the integrator did over the whole run, for the screen (several
    /// lines, each with its units), or empty.
    virtual std::string
    summary() const
    {
      return {};
    }
  };

  using IntegratorRegistry = Registry<Interface, ParameterHandler &>;
} // namespace tissuefem::time

/// Registers a time integrator at the end of its source file. @p Class must
/// be constructible from a ParameterHandler (which it may enter and leave
/// subsections of) and have a static
/// declare_parameters(ParameterHandler &).
#define TISSUEFEM_REGISTER_INTEGRATOR(Class, name, description) \
  namespace                                                     \
  {                                                             \
    const bool tissuefem_registered_##Class = [] {              \
      ::tissuefem::time::IntegratorRegistry::instance().add(    \
        name,                                                   \
        description,                                            \
        &Class::declare_parameters,                             \
        [](::dealii::ParameterHandler &prm) {                   \
          return std::unique_ptr<::tissuefem::time::Interface>( \
            std::make_unique<Class>(prm));                      \
        });                                                     \
      return true;                                              \
    }();                                                        \
  }
