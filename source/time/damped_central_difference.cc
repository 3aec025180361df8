#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/base/timing.h>
#include <tissuefem/time/first_order_system.h>
#include <tissuefem/time/interface.h>
#include <tissuefem/time/nodal.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace tissuefem::time
{
  /**
   * Jeffrey's damped explicit scheme with variable step (report eqs 10-11
   * and appendix A; solved for the new position as erratum J9
   * (doc/references.md), gives it): with the row-sum lumped mass m,
   * mass-proportional damping gamma = c m, the old step dt and the new step eta
   * dt,
   *
   *   u+ = [eta (eta + 1) dt^2 F / m + (2 (eta + 1) - c (eta^2 - 1) dt) u
   *         - eta (2 - c eta dt) u-] / (2 + c dt),   F = f_ext(t) - f_int(u),
   *
   * which for eta = 1 is the damped central difference, second-order
   * accurate. Only internal forces are evaluated (no matrix, no solve).
   * The first step starts from u- = u0 - dt v0 + dt^2/2 a0 with a0 from the
   * equation of motion. At start the critical step 2/omega_max (sqrt(1 +
   * xi^2) - xi), xi = c/(2 omega_max), is estimated by power iteration on
   * M^-1 K (K applied as differences of internal forces) and printed; a
   * larger 'Time step' is refused unless 'Allow unstable step' is set. A
   * run stops at the first step whose displacement is not finite, exceeds
   * a thousand times the body's size, or (tested every tenth step) whose
   * stored plus kinetic energy grew ten-thousandfold in ten steps.
   * Row-sum lumping is positive for P1 and Q_k elements; it is not for P2
   * tetrahedra, which are refused. The velocity reported at t_{n+1} is
   * (u_{n+1} - u_n)/h, the acceleration that of t_n.
   */
  class DampedCentralDifference : public Interface
  {
  public:
    explicit DampedCentralDifference(ParameterHandler &prm)
    {
      prm.enter_subsection("Time integration");
      prm.enter_subsection("Damped central difference");
      damping        = get_damping_ratio(prm);
      allow_unstable = prm.get_bool("Allow unstable step");
      threshold      = prm.get_double("Active region threshold");
      prm.leave_subsection();
      prm.leave_subsection();
      require(std::isfinite(threshold) && threshold >= 0,
              "Time integration/Damped central difference/Active region "
              "threshold",
              "must be >= 0 (force units; 0 propagates every node)");
      check_damping_ratio(damping,
                          "Time integration/Damped central difference/");
    }

    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Damped central difference");
      declare_damping_ratio(prm,
                            "Mass-proportional damping gamma/m (1/s if SI): "
                            "the damping force on node i is -gamma_i v_i with "
                            "gamma_i = ratio * m_i (Jeffrey eq 10).");
      prm.declare_entry("Active region threshold",
                        "0",
                        Patterns::Double(0),
                        "Jeffrey's node freezing (report section 3), in "
                        "force units: a node whose net force is below this "
                        "and which is nearly at rest (m |v| / dt below this "
                        "too) is held where it is for the step, unless holding "
                        "it would add energy (its force pushes it on along "
                        "its motion: h f.v > m |v|^2); cells none of whose "
                        "nodes moved in the last step are not evaluated; "
                        "nodes whose prescribed displacement moves are "
                        "always propagated. 0: every node, every step "
                        "(exact scheme). Freezing never adds energy, so "
                        "any threshold is stable; the error against the "
                        "exact scheme falls with the threshold. It saves "
                        "work where most of the body rests; measure it "
                        "with parameters/studies/active_region.sh.");
      prm.declare_entry("Allow unstable step",
                        "false",
                        Patterns::Bool(),
                        "Run even if 'Time step' exceeds the estimated "
                        "critical step (to study instability); the run "
                        "then stops when the energy blows up.");
      prm.leave_subsection();
    }

    /// A penalty contact force of (u, t), but not with an active region:
    /// a frozen node would not feel an obstacle arrive.
    Capabilities
    capabilities() const override
    {
      Capabilities c;
      c.penalty_contact = threshold == 0;
      if (threshold > 0)
        c.taken_away = "an active region ('Time integration/Damped central "
                       "difference/Active region threshold' > 0) freezes "
                       "nodes, which would not feel an obstacle arrive";
      return c;
    }

    void
    initialize(Context &c, State &state) override
    {
      context     = &c;
      auto &solid = c.solid;
      check_mesh();
      mass = &solid.lumped_mass();
      set_up_active_region();
      for (unsigned int i = 0; i < local_size(state.u); ++i)
        if (!(local_entries(*mass)[i] > 0))
          throw InputError("Parameter 'Time integration/Integrator': the "
                           "row-sum lumped mass is not positive at some "
                           "node (P2 simplices); use linear elements or an "
                           "implicit integrator");
      // u- from a Taylor expansion backwards with the initial acceleration.
      const double dt = c.time.time_step;
      VectorType   a;
      acceleration(state.u, state.v, state.time, a);
      previous = state.u;
      previous.add(-dt, state.v, 0.5 * dt * dt, a);
      previous_step = dt;
      state.a       = a;

      critical_step = estimate_critical_step(state.u);
      parallel_tools::screen()
        << "damped central difference: estimated critical step "
        << critical_step << " (time units; largest angular frequency "
        << omega_max << " rad per time unit), step " << dt << std::endl;
      if (dt > critical_step && !allow_unstable)
        throw InputError(
          "Parameter 'Time integration/Time step': " + std::to_string(dt)
          + " exceeds the estimated critical step "
          + std::to_string(critical_step)
          + " of the explicit scheme (set 'Time integration/Damped central "
            "difference/Allow unstable step' to run anyway)");
      energy = total_energy(state.u, state.v);
    }

    StepReport
    advance(State &state, const double end_time) override
    {
      auto        &solid = context->solid;
      StepReport   report;
      const double h = std::min(context->time.time_step, end_time - state.time);
      const double dt  = previous_step;
      const double eta = h / dt;
      const double c   = damping;

      const auto start = std::chrono::steady_clock::now();
      VectorType force;
      if (threshold > 0)
        active_region_force(state, force);
      else
        net_force(state.u, state.time, force);
      report.assembly_seconds = seconds_since(start);

      VectorType    next(state.u);
      double       *x           = local_entries(next);
      const double *u           = local_entries(state.u);
      const double *um          = local_entries(previous);
      const double *f           = local_entries(force);
      const double *m           = local_entries(*mass);
      const double  denominator = 2. + c * dt;
      for (unsigned int i = 0; i < local_size(next); ++i)
        x[i] = (eta * (eta + 1) * dt * dt * f[i] / m[i]
                + (2. * (eta + 1) - c * (eta * eta - 1) * dt) * u[i]
                - eta * (2. - c * eta * dt) * um[i])
               / denominator;
      solid.apply_dirichlet_values(state.time + h, next);
      if (threshold > 0)
        update_active_region(state.u, force, dt, h, next);

      // The acceleration at t (F/m - c v), v at t from appendix A.
      VectorType a(force);
      double    *ap = local_entries(a);
      for (unsigned int i = 0; i < local_size(a); ++i)
        ap[i] = f[i] / m[i]
                - c * (x[i] + (eta * eta - 1) * u[i] - eta * eta * um[i])
                    / (eta * (eta + 1) * dt);

      VectorType v(next);
      v -= state.u;
      v /= h;
      // Energy taken out by the damping force over the step, c m v^2 h
      // with the step's mean velocity.
      if (c > 0)
        {
          const double *vp   = local_entries(v);
          double        work = 0;
          for (unsigned int i = 0; i < local_size(v); ++i)
            work += m[i] * vp[i] * vp[i];
          report.damping_work
            = c * h * Utilities::MPI::sum(work, parallel_tools::communicator());
        }
      previous      = state.u;
      previous_step = h;
      state.u.swap(next);
      state.v.swap(v);
      state.a.swap(a);
      state.time += h;
      report.dt = h;
      // Contact with friction moves its stick points (and takes the
      // friction bound of this state for the next force).
      solid.accept_step(state.u, state.time);
      check_stability(state, h);
      return report;
    }

    std::vector<VectorType *>
    history() override
    {
      return {&previous};
    }

    /// Without an active region the state is u, v, a, u- and the numbers
    /// below; the active region's masks are not written.
    bool
    checkpointable() const override
    {
      return threshold == 0;
    }

    std::vector<double>
    checkpoint_scalars() const override
    {
      return {previous_step,
              critical_step,
              omega_max,
              energy,
              double(steps_since_energy),
              double(steps),
              last_growth,
              growth_before};
    }

    void
    restore_scalars(const std::vector<double> &scalars) override
    {
      previous_step      = scalars.at(0);
      critical_step      = scalars.at(1);
      omega_max          = scalars.at(2);
      energy             = scalars.at(3);
      steps_since_energy = static_cast<unsigned int>(scalars.at(4));
      steps              = static_cast<unsigned int>(scalars.at(5));
      // (Checkpoints written before the growths were kept have six.)
      last_growth   = scalars.size() > 6 ? scalars[6] : 0;
      growth_before = scalars.size() > 7 ? scalars[7] : 0;
    }

    void
    mesh_changed() override
    {
      check_mesh();
      mass = &context->solid.lumped_mass();
      set_up_active_region();
      // Smaller cells have higher frequencies: the step that was stable
      // may no longer be (estimated at the last state, which is on the new
      // mesh now).
      critical_step = estimate_critical_step(previous);
      if (context->time.time_step > critical_step && !allow_unstable)
        throw SolverError(
          "the mesh change lowered the explicit scheme's estimated critical "
          "step to "
          + std::to_string(critical_step) + ", below 'Time integration/Time "
          + "step' " + std::to_string(context->time.time_step)
          + " (refine less, or take a shorter step)");
    }

    std::string
    summary() const override
    {
      if (threshold == 0 || steps == 0)
        return {};
      std::ostringstream s;
      s << std::setprecision(3) << "active region: on average "
        << 100. * nodes_propagated / steps << " % of the degrees of freedom "
        << "propagated and " << 100. * cells_evaluated / steps
        << " % of this process's cells evaluated per step (threshold "
        << threshold << " force units)";
      return s.str();
    }

  private:
    double            damping        = 0;
    bool              allow_unstable = false;
    Context          *context        = nullptr;
    const VectorType *mass           = nullptr;
    VectorType        previous;
    double            previous_step = 0;
    double            critical_step = 0;
    double            omega_max     = 0;
    double            energy        = 0;
    /// The energy's growth factors over the last ten-step window and the
    /// one before (0 where a window started at zero).
    double       last_growth = 0, growth_before = 0;
    unsigned int steps_since_energy = 0;
    // Active region: 1 on dofs propagated in the next step, 0 on frozen
    // ones; free = 1 on unconstrained dofs.
    double     threshold = 0;
    VectorType active, free;
    /// 1 on the dofs of the first ring (nodes with a complete force).
    VectorType   complete;
    double       nodes_propagated = 0, cells_evaluated = 0;
    unsigned int steps = 0;

    void
    check_mesh() const
    {
      if (context->solid.has_hanging_nodes())
        throw InputError("Parameter 'Time integration/Integrator': the "
                         "damped central difference uses lumped masses, "
                         "which are not condensed at hanging nodes; use it "
                         "without mesh refinement");
    }

    void
    set_up_active_region()
    {
      context->solid.initialize_vector(active);
      active = 1.;
      free   = active;
      context->solid.zero_constrained_entries(free);
    }

    /**
     * Freezes (keeps at u in @p next) the free nodes of the first ring
     * whose net force f = f_ext - f_int is below the threshold (Jeffrey's
     * rule, report section 3) and which is nearly at rest (m |v| / h,
     * the force that would stop its proposed motion v within a step, is
     * below the threshold too), provided the freeze does not add energy.
     *
     * Why the proviso: without damping and for a linear model, the central
     * difference conserves exactly
     *   Q = 1/2 v^T M v + 1/2 u_n^T K u_{n+1},  v = (u_{n+1} - u_n) / h,
     * which is positive below the critical step: that is its stability.
     * Holding node i at u_n instead of its proposed u_{n+1} changes Q by
     *   dQ_i = -1/2 m_i |v_i|^2 + 1/2 h f_i . v_i
     * (Q is linear in u_{n+1}, so freezes add up without cross terms). A
     * node frozen at rest stays neutral (v_i = h f_i / m_i gives dQ_i =
     * 0); a moving node frozen while its force pushes it on, f . v > 0,
     * adds energy. An earlier rule froze nodes whose proposed motion was
     * small, f and inertia nearly cancelling, as in a fast oscillation:
     * there dQ_i can be positive at every freeze; the muscle blew up at
     * 1e-2 N.
     * Here a node freezes only if dQ_i <= 0, i.e. h f_i . v_i <= m_i
     * |v_i|^2, so freezing never adds energy, at any threshold (for
     * nonlinear models to the order of the model's change within a step;
     * damping only removes more). The error against the exact scheme
     * falls with the threshold; a threshold above the forces that move
     * the tissue freezes it (and the error is then of order one), stably.
     *
     * Nodes whose prescribed displacement moves are always propagated.
     * The next step evaluates the cells within two rings of the
     * propagated nodes, so that they and their neighbours (the first
     * ring) get complete forces; a node further out stays frozen (none of
     * its neighbours moved, so its force is what it was when it froze,
     * and holding it at rest is neutral). Dofs come in blocks of dim per
     * node.
     */
    void
    update_active_region(const VectorType &u,
                         const VectorType &force,
                         const double      dt,
                         const double      h,
                         VectorType       &next)
    {
      double       *x              = local_entries(next);
      double       *on             = local_entries(active);
      const double *complete_force = local_entries(complete);
      const double *up = local_entries(u), *um = local_entries(previous),
                   *f = local_entries(force), *m = local_entries(*mass),
                   *is_free         = local_entries(free);
      const unsigned int n          = local_size(next);
      const unsigned int d          = context->solid.n_components();
      double             propagated = 0;
      for (unsigned int node = 0; node + d <= n; node += d)
        {
          double force_squared = 0, momentum_squared = 0, power = 0,
                 kinetic = 0;
          bool moved     = false;
          for (unsigned int k = node; k < node + d; ++k)
            {
              // The undamped scheme's proposed velocity (the energy
              // argument is for it; damping only removes more). From rest
              // it is h f / m, so holding a resting node gives dQ = 0.
              const double v
                = (up[k] - um[k]) / dt + 0.5 * (h + dt) * f[k] / m[k];
              force_squared += f[k] * f[k];
              momentum_squared += std::pow(m[k] * v / h, 2);
              power += h * f[k] * v;
              kinetic += m[k] * v * v;
              moved = moved || (is_free[k] == 0 && x[k] != up[k]);
            }
          const double limit = threshold * threshold;
          const bool   freeze
            = complete_force[node] == 0
              || (force_squared < limit && momentum_squared < limit
                  && power <= kinetic * (1. + 1e-12));
          const bool propagate = moved || !freeze;
          for (unsigned int k = node; k < node + d; ++k)
            {
              on[k] = propagate ? 1. : 0.;
              if (!propagate && is_free[k] > 0)
                x[k] = up[k];
            }
          propagated += propagate ? d : 0;
        }
      nodes_propagated
        += Utilities::MPI::sum(propagated, parallel_tools::communicator())
           / context->solid.n_dofs();
      ++steps;
    }

    /**
     * The net force of a step with an active region: internal forces on
     * the cells within two rings of the moving nodes only. Every node of
     * the first ring (moving nodes and their neighbours) then gets its
     * complete force, the only force a frozen node may wake on.
     */
    void
    active_region_force(const State &state, VectorType &force)
    {
      auto &solid = context->solid;
      solid.mark_dofs_of(solid.cells_touching(active), complete);
      const auto cells = solid.cells_touching(complete);
      VectorType external;
      // The nodes of the first ring get the same force either way;
      // the others are frozen whatever their force. Where most cells
      // are needed, all are evaluated, with all threads.
      const auto n_cells = std::count(cells.begin(), cells.end(), true);
      if (2 * n_cells > static_cast<long>(cells.size()))
        solid.internal_force(state.u, force);
      else
        solid.internal_force_on(state.u, cells, force);
      solid.external_force(state.time, external);
      force.sadd(-1., 1., external);
      cells_evaluated += n_cells / double(cells.size());
    }

    /// Stops the run (SolverError) at the signs of instability after a
    /// step of size @p h to @p state: a displacement that is not finite or
    /// far too large, or a stored plus kinetic energy that exploded.
    void
    check_stability(const State &state, const double h)
    {
      auto &solid = context->solid;
      if (!all_finite(state.u))
        throw SolverError("the explicit scheme is unstable: it diverged at t = "
                          + std::to_string(state.time) + " (step "
                          + std::to_string(h) + ", estimated critical step "
                          + std::to_string(critical_step)
                          + "); nothing was written for this step");
      // Slow exponential growth (a step just above the critical one)
      // escapes the energy test below; no stable motion of a solid carries
      // it a thousand times its size away.
      if (state.u.linfty_norm() > 1e3 * solid.length_scale())
        throw SolverError("the explicit scheme is unstable at t = "
                          + std::to_string(state.time)
                          + ": displacements exceed 1000 times the body's "
                            "size (step "
                          + std::to_string(h) + ", estimated critical step "
                          + std::to_string(critical_step) + ")");
      // The energy test costs a pass over the cells: every tenth step,
      // against the energy ten steps before. An unstable mode grows by the
      // same factor in every window, far beyond what a damped or
      // conservative solid under bounded loads does. But a body at rest
      // (energy at round-off) that a load or an obstacle starts to move
      // grows without bound in the window where it starts; if it starts in
      // that window's last step, by a fraction f of a step, the next window
      // grows by (10 + f)^2 / f^2, above 1e4 for f < 0.1; after that, by
      // (20 + f)^p / (10 + f)^p, at most 2^8 = 256 for energy ~ t^p with
      // p <= 8. So three windows in a row must grow: more than 1e3 times
      // in each of the two before and 1e4 times in this one. (With one
      // window, a probe touching Jeffrey's muscle at rest stopped the
      // explicit run as unstable at first contact.)
      if (++steps_since_energy == 10)
        {
          steps_since_energy      = 0;
          const double new_energy = total_energy(state.u, state.v);
          const double growth     = energy > 0 ? new_energy / energy : 0;
          if (growth > 1e4 && last_growth > 1e3 && growth_before > 1e3)
            {
              std::ostringstream why;
              why << std::setprecision(3)
                  << "the explicit scheme is unstable at t = " << state.time
                  << ": stored plus kinetic energy grew from " << energy
                  << " to " << new_energy
                  << " (energy units) in ten steps, after growing "
                  << growth_before << " and " << last_growth
                  << " times in the two windows of ten before (step " << h
                  << ", estimated critical step " << critical_step << ")";
              throw SolverError(why.str());
            }
          growth_before = last_growth;
          last_growth   = growth;
          energy        = new_energy;
        }
    }

    /// F = f_ext(t) - f_int(u), the force driving the nodes (contact at
    /// t included).
    void
    net_force(const VectorType &u, const double time, VectorType &force) const
    {
      VectorType external;
      context->solid.internal_force(u, time, force);
      context->solid.external_force(time, external);
      force.sadd(-1., 1., external);
    }

    /// a = (f_ext(t) - f_int(u) - c m v) / m.
    void
    acceleration(const VectorType &u,
                 const VectorType &v,
                 const double      time,
                 VectorType       &a) const
    {
      net_force(u, time, a);
      double       *ap = local_entries(a);
      const double *vp = local_entries(v);
      const double *m  = local_entries(*mass);
      for (unsigned int i = 0; i < local_size(a); ++i)
        ap[i] = ap[i] / m[i] - damping * vp[i];
    }

    double
    total_energy(const VectorType &u, const VectorType &v)
    {
      return context->solid.stored_energy(u) + context->solid.kinetic_energy(v);
    }

    /**
     * omega_max^2 = largest eigenvalue of M^-1 K(u), by power iteration
     * with K w ~ (f_int(u + e w) - f_int(u)) / e on the free entries;
     * 10 % is added for the estimate's shortfall, and the force
     * contributions' bound (Operators::contribution_frequency_bound()).
     */
    double
    estimate_critical_step(const VectorType &u)
    {
      auto      &solid = context->solid;
      VectorType w(u), base, shifted, trial;
      solid.internal_force(u, base);
      // A deterministic start with every mode in it.
      double *wp = local_entries(w);
      for (unsigned int i = 0; i < local_size(w); ++i)
        wp[i] = 1. + 0.37 * std::sin(1.7 * (i + 1) + w.local_range().first);
      solid.zero_constrained_entries(w);
      double lambda = 0;
      for (unsigned int k = 0; k < 40; ++k)
        {
          const double norm = w.l2_norm();
          if (!(norm > 0))
            break;
          w /= norm;
          const double e = 1e-7 * (1. + u.linfty_norm());
          trial          = u;
          trial.add(e, w);
          solid.internal_force(trial, shifted);
          shifted -= base;
          shifted /= e;
          double       *sp = local_entries(shifted);
          const double *m  = local_entries(*mass);
          for (unsigned int i = 0; i < local_size(shifted); ++i)
            sp[i] /= m[i];
          solid.zero_constrained_entries(shifted);
          lambda = shifted * w;
          w      = shifted;
        }
      // Contact may touch anywhere later: its bound, not today's state.
      omega_max = std::sqrt(std::max(lambda, 0.) * 1.1
                            + solid.contribution_frequency_bound());
      if (!(omega_max > 0))
        return std::numeric_limits<double>::infinity();
      const double xi = damping / (2. * omega_max);
      return 2. / omega_max * (std::sqrt(1. + xi * xi) - xi);
    }
  };

  TISSUEFEM_REGISTER_INTEGRATOR(
    DampedCentralDifference,
    "damped central difference",
    "Jeffrey's explicit scheme (report eqs 10-11) with lumped mass, "
    "mass-proportional damping and variable step; conditionally stable, "
    "second order.")
} // namespace tissuefem::time
