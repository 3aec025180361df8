#include <deal.II/lac/trilinos_parallel_block_vector.h>
#include <deal.II/sundials/arkode.h>
#include <deal.II/sundials/n_vector.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/timing.h>
#include <tissuefem/time/error_norm.h>
#include <tissuefem/time/first_order_system.h>
#include <tissuefem/time/interface.h>
#include <tissuefem/time/nodal.h>
#include <tissuefem/time/radau_linear_systems.h>
#include <tissuefem/time/stiffness.h>

#include <arkode/arkode_arkstep.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <sstream>

namespace tissuefem::time
{
  using BlockVectorType = TrilinosWrappers::MPI::BlockVector;

  /**
   * SUNDIALS' ARKode (Reynolds, Gardner, Hindmarsh et al.) through deal.II's
   * SUNDIALS::ARKode, for the first-order form of Jeffrey's eq 10 with the
   * row-sum lumped mass m and mass-proportional damping c (as Radau IIA):
   *
   *   y = (u, v),   u' = v,   v' = (f_ext(t) - f_int(u)) / m - c v.
   *
   * 'Method = explicit': an adaptive explicit Runge-Kutta method of the
   * chosen order (ARKode's embedded ERK pairs); only internal forces are
   * evaluated. 'Method = implicit': an adaptive diagonally implicit method
   * (ARKode's SDIRK/ESDIRK tables) whose stage equations ARKode solves by
   * Newton's method; each Newton system (I - gamma J) x = b, J = [0 I;
   * -K/m -c], is reduced to the displacements, (K + s M) x_u = M (...),
   * s = sigma (sigma + c), sigma = 1/gamma, and solved with the sparse
   * direct solver (RadauLinearSystems' real system). K is the stiffness
   * of 'Jacobian' (analytical, numerical or simplified, as for Radau IIA),
   * evaluated when ARKode asks for a Jacobian update and refactorized when
   * gamma moved by more than 20 % since the last factorization (ARKode's
   * own threshold for reusing a Newton matrix).
   *
   * Each call of advance() propagates over one 'Time step' with as many
   * ARKode steps as its error control takes, and stops exactly at the
   * interval's end (ARKode's stop time). Prescribed displacements enter
   * every right-hand side evaluation from their expression at that time;
   * their entries of y are inert (zero derivative). deal.II 9.4's wrapper
   * neither catches exceptions from callbacks nor checks ARKode's return
   * codes in release builds, so this class sets ARKode up through the
   * wrapper (reset()) and calls ARKStepEvolve itself, checking every
   * status: a failure ends the run with a SolverError naming ARKode's
   * code.
   */
  class ARKodeIntegrator : public Interface
  {
  public:
    explicit ARKodeIntegrator(ParameterHandler &prm)
    {
      prm.enter_subsection("Time integration");
      prm.enter_subsection("ARKode");
      method               = prm.get("Method");
      order                = prm.get_integer("Order");
      const double damping = get_damping_ratio(prm);
      jacobian_kind        = prm.get("Jacobian");
      every_iteration      = prm.get("Jacobian update") == "iteration";
      max_steps            = prm.get_integer("Maximum steps per interval");
      adaptive             = prm.get_bool("Adaptive step");
      tolerances.parse_parameters(prm, "Time integration/ARKode/");
      prm.leave_subsection();
      prm.leave_subsection();
      check_damping_ratio(damping, "Time integration/ARKode/");
      require(method == "explicit" || order <= 5,
              "Time integration/ARKode/Order",
              "must be 2 to 5 for the implicit method (ARKode's DIRK "
              "tables), got "
                + std::to_string(order));
      system    = std::make_unique<FirstOrderSystem>(damping,
                                                  "ARKode",
                                                  " or backward Euler");
      stiffness = std::make_unique<Stiffness>(jacobian_kind);
    }

    ~ARKodeIntegrator() override
    {
      // The solver's memory refers to the context's vectors: free it first.
      ode.reset();
      if (context_ready)
        SUNContext_Free(&sundials_context);
    }

    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("ARKode");
      prm.declare_entry("Method",
                        "implicit",
                        Patterns::Selection("explicit|implicit"),
                        "explicit: ARKode's adaptive explicit Runge-Kutta "
                        "(internal forces only; the step is bounded by "
                        "stability, about the critical step of the central "
                        "difference). implicit: ARKode's adaptive "
                        "diagonally implicit Runge-Kutta with Newton's "
                        "method on the stage equations.");
      prm.declare_entry("Order",
                        "4",
                        Patterns::Integer(2, 8),
                        "Order of accuracy of ARKode's method table: 2-8 "
                        "explicit, 2-5 implicit.");
      declare_damping_ratio(prm, first_order_damping_documentation);
      prm.declare_entry("Jacobian",
                        "analytical",
                        Patterns::Selection(Stiffness::choices()),
                        "The stiffness in the Newton matrix of the implicit "
                        "method: analytical (the AD tangent), numerical "
                        "(differenced forces) or simplified (none).");
      prm.declare_entry("Jacobian update",
                        "iteration",
                        Patterns::Selection("iteration|stage"),
                        "When the implicit method re-evaluates K: at every "
                        "Newton iteration (full Newton: robust at large "
                        "fixed steps) or at the first iteration of each "
                        "stage and after a convergence failure (modified "
                        "Newton: fewer assemblies, but at fixed steps a "
                        "failure ends the run, since ARKode answers it by "
                        "shrinking the step).");
      prm.declare_entry("Maximum steps per interval",
                        "100000",
                        Patterns::Integer(1),
                        "ARKode steps allowed within one 'Time step' before "
                        "the run stops with an error.");
      prm.declare_entry("Adaptive step",
                        "true",
                        Patterns::Bool(),
                        "Choose ARKode's steps from its error estimate; "
                        "false takes steps of exactly 'Time step' (for "
                        "order studies).");
      ErrorTolerances::declare_parameters(prm);
      prm.leave_subsection();
    }

    void
    initialize(Context &c, State &state) override
    {
      context = &c;
      // Its Newton systems multiply with the Jacobian itself (Stiffness).
      c.solid.solve_only_through_operators(false, c.linear_solver);
      if (!context_ready)
        {
          MPI_Comm comm = parallel_tools::communicator();
          SUNContext_Create(&comm, &sundials_context);
          context_ready = true;
        }
      set_up(state);
      if (derivative(state.time, y, f) != 0)
        throw SolverError("ARKode: the initial state cannot be evaluated "
                          "(inverted elements)");
      state.a = f.block(1);
    }

    StepReport
    advance(State &state, const double end_time) override
    {
      StepReport   report;
      const auto   start = std::chrono::steady_clock::now();
      const double target
        = std::min(state.time + context->time.time_step, end_time);
      if (!ode)
        start_solver(state);
      auto counters_before = counters();
      jacobian_evaluations = 0;
      linear_solves        = 0;
      rhs_failure.clear();

      void *memory = ode->get_arkode_memory();
      int   status = ARKStepSetStopTime(memory, target);
      check(status, "ARKStepSetStopTime", state.time);
      auto   view = SUNDIALS::internal::make_nvector_view(y, sundials_context);
      double reached = state.time;
      status = ARKStepEvolve(memory, target, view, &reached, ARK_NORMAL);
      if (!rhs_failure.empty())
        throw SolverError("ARKode: " + rhs_failure);
      check(status, "ARKStepEvolve", reached);

      const auto counters_after = counters();
      report.substeps
        = static_cast<unsigned int>(counters_after[0] - counters_before[0]);
      report.newton_iterations
        = static_cast<unsigned int>(counters_after[1] - counters_before[1]);
      report.rejected_attempts
        = static_cast<unsigned int>(counters_after[2] - counters_before[2]);
      report.linear_iterations    = linear_solves;
      report.jacobian_evaluations = jacobian_evaluations;

      // The new state; prescribed entries from their expression, their
      // velocity as the interval's difference quotient.
      const double h     = target - state.time;
      VectorType   old_u = state.u;
      state.u            = y.block(0);
      context->solid.apply_dirichlet_values(target, state.u);
      state.v = y.block(1);
      VectorType boundary_velocity(state.u);
      boundary_velocity -= old_u;
      boundary_velocity /= h;
      double       *vp = local_entries(state.v);
      const double *bp = local_entries(boundary_velocity);
      const double *fr = local_entries(system->free());
      for (unsigned int i = 0; i < local_size(state.v); ++i)
        if (!(fr[i] > 0))
          vp[i] = bp[i];
      // Damping work c int v^T m v dt by the trapezoidal rule over the
      // interval (an estimate: ARKode's stages are not seen here).
      const double power_end = system->damping_power(state.v);
      report.damping_work    = 0.5 * h * (power_start + power_end);
      power_start            = power_end;
      derivative(target, y, f);
      state.a                 = f.block(1);
      state.time              = target;
      report.dt               = h;
      report.assembly_seconds = seconds_since(start) - solve_seconds;
      report.solve_seconds    = solve_seconds;
      solve_seconds           = 0;
      return report;
    }

    Capabilities
    capabilities() const override
    {
      Capabilities c;
      // The explicit method never asks for the stiffness.
      if (jacobian_kind == "numerical" && method != "explicit")
        c.whole_mesh_parameter = "Time integration/ARKode/Jacobian";
      return c;
    }

    void
    mesh_changed() override
    {
      // New constraints (a tool grasped or let go): start ARKode anew from
      // the state at the next advance().
      ode.reset();
      stiffness->reset();
    }

  private:
    std::string     method, jacobian_kind;
    unsigned int    order           = 4;
    unsigned int    max_steps       = 100000;
    bool            adaptive        = true;
    bool            every_iteration = true;
    ErrorTolerances tolerances;
    Context        *context = nullptr;

    SUNContext sundials_context = nullptr;
    bool       context_ready    = false;
    std::unique_ptr<SUNDIALS::ARKode<BlockVectorType>> ode;
    BlockVectorType                                    y, f, absolute;
    // Damping ratio, lumped mass and the mask of free entries.
    std::unique_ptr<FirstOrderSystem>   system;
    std::unique_ptr<Stiffness>          stiffness;
    std::unique_ptr<RadauLinearSystems> systems;
    double                              factorized_gamma = 0;
    /// ARKode's step and convergence-failure counts at the last evaluation
    /// of K (-1: none since the solver started).
    long int     stiffness_steps = -1, stiffness_failures = 0;
    double       stiffness_time       = 0;
    bool         stiffness_fresh      = false;
    unsigned int jacobian_evaluations = 0, linear_solves = 0;
    double       solve_seconds = 0, power_start = 0;
    std::string  rhs_failure;

    /// Vectors, masks and the lumped mass for the current mesh.
    void
    set_up(const State &state)
    {
      system->reinit(context->solid, state.u);
      const IndexSet owned = state.u.locally_owned_elements();
      y.reinit(std::vector<IndexSet>{owned, owned},
               parallel_tools::communicator());
      f.reinit(y);
      absolute.reinit(y);
      absolute.block(0) = tolerances.absolute_u;
      absolute.block(1) = tolerances.absolute_v;
      y.block(0)        = state.u;
      y.block(1)        = state.v;
      systems
        = std::make_unique<RadauLinearSystems>(system->damping(), 1., 0., 0.);
      systems->reinit(system->mass(),
                      system->free(),
                      stiffness->assembled(),
                      context->linear_solver);
      factorized_gamma = 0;
      stiffness_steps  = -1;
      power_start      = system->damping_power(state.v);
    }

    /// f(t, y); returns ARKode's code: 0, or 1 (recoverable: a state the
    /// material cannot evaluate, ARKode retries with a smaller step).
    int
    derivative(const double t, const BlockVectorType &x, BlockVectorType &fx)
    {
      auto      &solid = context->solid;
      VectorType u(x.block(0)), internal, external;
      solid.apply_dirichlet_values(t, u);
      try
        {
          solid.internal_force(u, internal);
        }
      catch (const SolverError &)
        {
          return 1;
        }
      solid.external_force(t, external);
      const double *m       = local_entries(system->mass());
      const double *fr      = local_entries(system->free());
      const double  damping = system->damping();
      const double *fi = local_entries(internal), *fe = local_entries(external);
      const double *v  = local_entries(x.block(1));
      double       *du = local_entries(fx.block(0));
      double       *dv = local_entries(fx.block(1));
      for (unsigned int i = 0; i < local_size(u); ++i)
        {
          du[i] = fr[i] * v[i];
          dv[i] = fr[i] * ((fe[i] - fi[i]) / m[i] - damping * v[i]);
        }
      return 0;
    }

    /// Builds the ARKode object and its callbacks, starting from @p state.
    void
    start_solver(const State &state)
    {
      set_up(state);
      typename SUNDIALS::ARKode<BlockVectorType>::AdditionalData data;
      data.initial_time                  = state.time;
      data.final_time                    = context->time.end_time;
      data.initial_step_size             = context->time.time_step;
      data.output_period                 = context->time.time_step;
      data.maximum_order                 = order;
      data.relative_tolerance            = tolerances.relative;
      data.absolute_tolerance            = tolerances.absolute_u;
      data.maximum_non_linear_iterations = 4;
      ode = std::make_unique<SUNDIALS::ARKode<BlockVectorType>>(
        data, parallel_tools::communicator());
      ode->get_local_tolerances
        = [this]() -> BlockVectorType & { return absolute; };
      auto rhs = [this](const double           t,
                        const BlockVectorType &x,
                        BlockVectorType       &fx) -> int {
        try
          {
            return derivative(t, x, fx);
          }
        catch (const std::exception &e)
          {
            // Nothing may be thrown through SUNDIALS' C code.
            rhs_failure = e.what();
            return -1;
          }
      };
      if (method == "explicit")
        ode->explicit_function = rhs;
      else
        {
          ode->implicit_function    = rhs;
          ode->jacobian_times_setup = [this](double                 t,
                                             const BlockVectorType &x,
                                             const BlockVectorType &) {
            return guarded([&] { evaluate_stiffness(t, x); });
          };
          ode->jacobian_times_vector = [this](const BlockVectorType &v,
                                              BlockVectorType       &Jv,
                                              double,
                                              const BlockVectorType &,
                                              const BlockVectorType &) {
            return guarded([&] { multiply_jacobian(v, Jv); });
          };
          ode->solve_linearized_system
            = [this](SUNDIALS::SundialsOperator<BlockVectorType> &,
                     SUNDIALS::SundialsPreconditioner<BlockVectorType> &,
                     BlockVectorType       &x,
                     const BlockVectorType &b,
                     double) { return guarded([&] { solve(x, b); }); };
        }
      ode->reset(state.time, context->time.time_step, y);
      void *memory = ode->get_arkode_memory();
      // Let ARKode estimate the first step; bound the work per interval.
      if (adaptive)
        check(ARKStepSetInitStep(memory, 0.), "ARKStepSetInitStep", state.time);
      else
        check(ARKStepSetFixedStep(memory, context->time.time_step),
              "ARKStepSetFixedStep",
              state.time);
      check(ARKStepSetMaxNumSteps(memory, max_steps),
            "ARKStepSetMaxNumSteps",
            state.time);
    }

    /// Runs @p work, turning exceptions into ARKode's failure code.
    template <typename Work>
    int
    guarded(const Work &work)
    {
      try
        {
          work();
          return 0;
        }
      catch (const SolverError &)
        {
          return 1;
        }
      catch (const std::exception &e)
        {
          rhs_failure = e.what();
          return -1;
        }
    }

    /**
     * ARKode calls this before every linear solve (the product J v may
     * depend on the iterate): with 'Jacobian update = iteration' K is
     * evaluated each time (full Newton). With 'stage' it is kept within a
     * stage instead (modified Newton on each stage equation) and re-evaluated
     * at the first solve of each new stage (a new time t) or after a nonlinear
     * convergence failure. (Keeping it for 20 steps, as ARKode keeps
     * matrix-based Newton matrices, made fixed-step runs fail: ARKode sees a
     * matrix-free solver and answers a failure by shrinking the step, not
     * by asking for a fresh Jacobian.)
     */
    void
    evaluate_stiffness(const double t, const BlockVectorType &x)
    {
      if (!stiffness->assembled())
        return;
      if (!every_iteration)
        {
          long int steps = 0, failures = 0;
          void    *memory = ode->get_arkode_memory();
          ARKStepGetNumSteps(memory, &steps);
          ARKStepGetNumNonlinSolvConvFails(memory, &failures);
          if (stiffness_steps >= 0 && steps == stiffness_steps
              && failures == stiffness_failures && t == stiffness_time)
            return;
          stiffness_steps    = steps;
          stiffness_failures = failures;
          stiffness_time     = t;
        }
      VectorType u(x.block(0));
      context->solid.apply_dirichlet_values(t, u);
      stiffness->evaluate(context->solid, u, t);
      ++jacobian_evaluations;
      stiffness_fresh = true;
    }

    /// Jv = (v_v, -(K v_u)/m - c v_v) on the free entries.
    void
    multiply_jacobian(const BlockVectorType &v, BlockVectorType &Jv) const
    {
      VectorType Kv(v.block(0));
      if (stiffness->assembled())
        stiffness->matrix().vmult(Kv, v.block(0));
      else
        Kv = 0.;
      const double *m       = local_entries(system->mass());
      const double *fr      = local_entries(system->free());
      const double  damping = system->damping();
      const double *k = local_entries(Kv), *vv = local_entries(v.block(1));
      double       *ju = local_entries(Jv.block(0));
      double       *jv = local_entries(Jv.block(1));
      for (unsigned int i = 0; i < local_size(Kv); ++i)
        {
          ju[i] = fr[i] * vv[i];
          jv[i] = fr[i] * (-k[i] / m[i] - damping * vv[i]);
        }
    }

    /// x = (I - gamma J)^-1 b = ((1/gamma) I - J)^-1 (b / gamma).
    void
    solve(BlockVectorType &x, const BlockVectorType &b)
    {
      const auto start = std::chrono::steady_clock::now();
      double     gamma = 0;
      check(ARKStepGetCurrentGamma(ode->get_arkode_memory(), &gamma),
            "ARKStepGetCurrentGamma",
            0.);
      if (stiffness_fresh || factorized_gamma == 0
          || std::abs(gamma / factorized_gamma - 1.) > 0.2)
        {
          systems->factorize(*stiffness, gamma, /*with_complex=*/false);
          factorized_gamma = gamma;
          stiffness_fresh  = false;
        }
      x = b;
      x /= factorized_gamma;
      systems->solve_real(factorized_gamma, x.block(0), x.block(1));
      ++linear_solves;
      solve_seconds += seconds_since(start);
    }

    /// Steps, nonlinear iterations and error-test failures so far.
    std::array<long int, 3>
    counters() const
    {
      std::array<long int, 3> c{{0, 0, 0}};
      void                   *memory = ode->get_arkode_memory();
      ARKStepGetNumSteps(memory, &c[0]);
      if (method == "implicit")
        ARKStepGetNumNonlinSolvIters(memory, &c[1]);
      ARKStepGetNumErrTestFails(memory, &c[2]);
      return c;
    }

    static void
    check(const int status, const char *call, const double time)
    {
      if (status >= 0)
        return;
      char             *name = ARKStepGetReturnFlagName(status);
      const std::string flag(name ? name : "unknown");
      std::free(name);
      throw SolverError("ARKode: " + std::string(call)
                        + " failed at t = " + std::to_string(time)
                        + " with code " + std::to_string(status) + " (" + flag
                        + "); try a looser tolerance, a smaller 'Time "
                          "step' or another integrator");
    }
  };

  TISSUEFEM_REGISTER_INTEGRATOR(
    ARKodeIntegrator,
    "ARKode",
    "SUNDIALS ARKode through deal.II: adaptive explicit Runge-Kutta or "
    "adaptive diagonally implicit Runge-Kutta with Newton's method, lumped "
    "mass and mass-proportional damping.")

  // Files written before the name was cased as SUNDIALS spells it.
  namespace
  {
    const bool arkode_earlier_spelling = [] {
      IntegratorRegistry::instance().add_alias("arkode", "ARKode");
      return true;
    }();
  } // namespace
} // namespace tissuefem::time
