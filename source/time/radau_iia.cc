#include <deal.II/base/tensor.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/base/timing.h>
#include <tissuefem/time/error_norm.h>
#include <tissuefem/time/interface.h>
#include <tissuefem/time/nodal.h>
#include <tissuefem/time/radau_linear_systems.h>
#include <tissuefem/time/stiffness.h>

#include <Epetra_CrsMatrix.h>

#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <sstream>

namespace tissuefem::time
{
  namespace
  {
    // The 3-stage Radau IIA method (Hairer and Wanner, Solving ODEs II,
    // IV.5 and their code RADAU5; Jeffrey appendix D with ERRATA item 8):
    // nodes c, and the transformation T with T^-1 A^-1 T = [gamma 0 0; 0
    // alpha -beta; 0 beta alpha].
    const double s6 = std::sqrt(6.);
    const double c1 = (4. - s6) / 10., c2 = (4. + s6) / 10.;
    const double gamma_hat = 3.637834252744496, alpha_hat = 2.681082873627752,
                 beta_hat = 3.050430199247411;
    const double T[3][3]  = {{9.1232394870892942792e-02,
                              -0.14125529502095420843,
                              -3.0029194105147424492e-02},
                             {0.24171793270710701896,
                              0.20412935229379993199,
                              0.38294211275726193779},
                             {0.96604818261509293619, 1., 0.}};
    const double TI[3][3] = {
      {4.3255798900631553510, 0.33919925181580986954, 0.54177053993587487119},
      {-4.1787185915519047273, -0.32768282076106238708, 0.47662355450055045196},
      {-0.50287263494578687595,
       2.5719269498556054292,
       -0.59603920482822492497}};
    // The Butcher matrix A (Hairer and Wanner, table IV.5.6), whose
    // inverse gives boundary velocities from prescribed stage
    // displacements.
    const double       A[3][3]   = {{(88. - 7. * s6) / 360.,
                                     (296. - 169. * s6) / 1800.,
                                     (-2. + 3. * s6) / 225.},
                                    {(296. + 169. * s6) / 1800.,
                                     (88. + 7. * s6) / 360.,
                                     (-2. - 3. * s6) / 225.},
                                    {(16. - s6) / 36., (16. + s6) / 36., 1. / 9.}};
    const Tensor<2, 3> inverse_a = invert(Tensor<2, 3>(A));
    // The error estimate's weights (ERRATA item 8, D.22, times gamma_hat).
    const double dd1 = -(13. + 7. * s6) / 3., dd2 = (-13. + 7. * s6) / 3.,
                 dd3 = -1. / 3.;
    // Quadrature weights b_i = a_3i.
    const double b1 = (16. - s6) / 36., b2 = (16. + s6) / 36., b3 = 1. / 9.;
  } // namespace

  /**
   * Jeffrey's implicit integrator (report section 3.3 and appendices D-E):
   * the 3-stage Radau IIA method, order 5, L-stable, with an adaptive step,
   * for the first-order form of eq 10 with the row-sum lumped mass m and
   * mass-proportional damping gamma = c m (eq D.18):
   *
   *   u' = v,   v' = (f_ext(t) - f_int(u)) / m - c v.
   *
   * Each call of advance() propagates over one 'Time step' (the report's
   * interval Delta t) with as many Runge-Kutta steps h as the error
   * estimate allows. The stage equations are solved by simplified Newton
   * in Hairer's transformed variables (D.16-D.17): one real system with
   * (gamma_hat/h) I - J and one complex with ((alpha_hat + i beta_hat)/h) I -
   * J. With J = [0 I; -K/m -c] each reduces to the displacements,
   * (K + s M) x = M (r_v + (sigma + c) r_u), s = sigma (sigma + c); the
   * complex one is solved as its real 2n x 2n form. 'Jacobian' selects K
   * (appendix E): analytical (the AD tangent), numerical (differenced
   * forces) or simplified (K = 0: diagonal, nothing assembled or
   * factorized). The Jacobian is re-evaluated at the start of a step only
   * when the previous Newton iteration contracted slowly (theta > 0.001),
   * and the matrices are refactorized when h changes by more than 20 %,
   * as RADAU5 does. Step size control, Newton stopping test and starting
   * values (the collocation polynomial of the last step, D.19 and
   * D.24-D.26 corrected) follow RADAU5; the embedded error estimate is
   * D.21-D.22.
   */
  class RadauIIA : public Interface
  {
  public:
    explicit RadauIIA(ParameterHandler &prm)
    {
      prm.enter_subsection("Time integration");
      prm.enter_subsection("Radau IIA");
      damping       = prm.get_double("Damping ratio");
      jacobian_kind = prm.get("Jacobian");
      tolerances.parse_parameters(prm, "Time integration/Radau IIA/");
      adaptive   = prm.get_bool("Adaptive step");
      max_newton = prm.get_integer("Maximum Newton iterations");
      prm.leave_subsection();
      prm.leave_subsection();
      const std::string section = "Time integration/Radau IIA/";
      require(std::isfinite(damping) && damping >= 0,
              section + "Damping ratio",
              "must be >= 0");
      stiffness = std::make_unique<Stiffness>(jacobian_kind);
    }

    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Radau IIA");
      prm.declare_entry("Damping ratio",
                        "0",
                        Patterns::Double(0),
                        "Mass-proportional damping gamma/m (1/s if SI), as "
                        "in the damped central difference (Jeffrey eq 10).");
      prm.declare_entry("Jacobian",
                        "analytical",
                        Patterns::Selection(Stiffness::choices()),
                        "The stiffness in the Newton matrix (Jeffrey "
                        "appendix E): analytical = the automatically "
                        "differentiated tangent; numerical = forward "
                        "differences of the internal force; simplified = "
                        "none (mass and damping only, never assembled).");
      ErrorTolerances::declare_parameters(prm);
      prm.declare_entry("Adaptive step",
                        "true",
                        Patterns::Bool(),
                        "Choose the Runge-Kutta step from the error "
                        "estimate; false takes steps of 'Time step' "
                        "(halved only when Newton fails), for order "
                        "studies.");
      prm.declare_entry("Maximum Newton iterations",
                        "7",
                        Patterns::Integer(1, 100),
                        "Simplified Newton iterations per Runge-Kutta step "
                        "before the step is retried with a smaller h.");
      prm.leave_subsection();
    }

    void
    initialize(Context &c, State &state) override
    {
      context = &c;
      check_mesh();
      set_up_vectors(state.u);
      derivative(state.time, state.u, state.v, f0u, f0v);
      state.a = f0v;
      h       = c.time.time_step;
    }

    StepReport
    advance(State &state, const double end_time) override
    {
      StepReport   report;
      const auto   start = std::chrono::steady_clock::now();
      const double target
        = std::min(state.time + context->time.time_step, end_time);
      const double interval_start = state.time;
      report.substeps             = 0;
      while (target - state.time > 1e-12 * context->time.time_step)
        {
          if (!adaptive)
            h = std::min(h, context->time.time_step);
          double step = h;
          // Do not leave a sliver to the end of the interval.
          const bool clipped = state.time + 1.05 * step >= target;
          if (clipped)
            step = target - state.time;
          if (stiffness->assembled() && !jacobian_current)
            {
              const auto assembly_start = std::chrono::steady_clock::now();
              stiffness->evaluate(context->solid, state.u, state.time);
              report.assembly_seconds += seconds_since(assembly_start);
              ++report.jacobian_evaluations;
              jacobian_current = jacobian_fresh = true;
              factorized_step                   = 0;
            }
          const Attempt attempt = try_step(state, step);
          report.newton_iterations += attempt.newton_iterations;
          if (!attempt.converged || (adaptive && attempt.error >= 1.))
            {
              ++report.rejected_attempts;
              h = attempt.next_step;
              if (h < 1e-10 * context->time.time_step)
                throw SolverError(
                  "Radau IIA: the Runge-Kutta step fell below 1e-10 times "
                  "the time step at t = "
                  + std::to_string(state.time)
                  + " (Newton does not converge or the error estimate "
                    "stays above the tolerance)");
              // Newton failed with a Jacobian of an older state: refresh.
              if (!attempt.converged && !jacobian_fresh)
                jacobian_current = false;
              continue;
            }
          accept(state, step, report);
          ++report.substeps;
          step_sum += step;
          // A step cut short at the interval's end says nothing against
          // the step the controller had.
          if (!adaptive)
            h = context->time.time_step;
          else if (!clipped || attempt.next_step < step)
            h = attempt.next_step;
        }
      report.dt = target - interval_start;
      ++intervals;
      totals.newton_iterations += report.newton_iterations;
      totals.jacobian_evaluations += report.jacobian_evaluations;
      totals.substeps += report.substeps;
      totals.rejected_attempts += report.rejected_attempts;
      report.solve_seconds = seconds_since(start) - report.assembly_seconds;
      return report;
    }

    void
    mesh_changed() override
    {
      check_mesh();
      VectorType u;
      context->solid.initialize_vector(u);
      set_up_vectors(u);
      stiffness->reset();
      factorized_step  = 0;
      jacobian_current = false;
      have_polynomial  = false;
    }

    std::string
    summary() const override
    {
      std::ostringstream s;
      const double       n = std::max(intervals, 1u);
      s << "Radau IIA (" << jacobian_kind << " Jacobian): " << intervals
        << " intervals of 'Time step'; per interval: mean Runge-Kutta step "
        << (totals.substeps > 0 ? step_sum / totals.substeps : 0.)
        << " (time units), Runge-Kutta steps " << totals.substeps / n
        << ", rejected " << totals.rejected_attempts / n
        << ", Jacobian evaluations " << totals.jacobian_evaluations / n
        << ", Newton iterations " << totals.newton_iterations / n;
      return s.str();
    }

  private:
    struct Attempt
    {
      bool         converged         = false;
      unsigned int newton_iterations = 0;
      double       error             = 0;
      double       next_step         = 0;
    };

    // Parameters.
    double          damping = 0;
    ErrorTolerances tolerances;
    std::string     jacobian_kind;
    bool            adaptive   = true;
    unsigned int    max_newton = 7;

    Context                   *context = nullptr;
    std::unique_ptr<Stiffness> stiffness;
    const VectorType          *mass = nullptr;
    VectorType                 free; // 1 on free entries, 0 on constrained

    // Stage increments Z, transformed W, derivatives F, the polynomial of
    // the last step (for starting values), and f at the step's start.
    std::array<VectorType, 3> zu, zv, wu, wv, fu, fv, pu, pv;
    VectorType                f0u, f0v;
    bool                      have_polynomial = false;
    double                    last_step       = 0;

    // Newton's two linear systems, built for the step factorized_step.
    std::unique_ptr<RadauLinearSystems> systems;
    double                              factorized_step  = 0;
    bool                                jacobian_current = false;

    double       h         = 0;
    double       faccon    = 1;
    double       theta     = 1;
    double       step_sum  = 0;
    unsigned int intervals = 0;
    StepReport   totals;
    bool         jacobian_fresh = false; // evaluated at the present state

    void
    check_mesh() const
    {
      if (context->solid.has_hanging_nodes())
        throw InputError("Parameter 'Time integration/Integrator': Radau IIA "
                         "uses lumped masses, which are not condensed at "
                         "hanging nodes; use it without mesh refinement");
    }

    void
    set_up_vectors(const VectorType &like)
    {
      auto &solid = context->solid;
      mass        = &solid.lumped_mass();
      for (unsigned int i = 0; i < local_size(like); ++i)
        if (!(local_entries(*mass)[i] > 0))
          throw InputError("Parameter 'Time integration/Integrator': the "
                           "row-sum lumped mass is not positive at some "
                           "node (P2 simplices); use linear elements");
      free = like;
      free = 1.;
      solid.zero_constrained_entries(free);
      for (auto *set : {&zu, &zv, &wu, &wv, &fu, &fv, &pu, &pv})
        for (auto &v : *set)
          v.reinit(like, false);
      f0u.reinit(like, false);
      f0v.reinit(like, false);
      if (!systems)
        systems = std::make_unique<RadauLinearSystems>(damping,
                                                       gamma_hat,
                                                       alpha_hat,
                                                       beta_hat);
      systems->reinit(*mass,
                      free,
                      stiffness->assembled(),
                      context->linear_solver);
    }

    /// f(t, y) for y = (u, v): (v, (f_ext - f_int(u))/m - c v).
    void
    derivative(const double      t,
               const VectorType &u,
               const VectorType &v,
               VectorType       &du,
               VectorType       &dv)
    {
      VectorType external;
      context->solid.internal_force(u, dv);
      context->solid.external_force(t, external);
      dv.sadd(-1., 1., external);
      double       *a = local_entries(dv);
      const double *m = local_entries(*mass), *vp = local_entries(v);
      for (unsigned int i = 0; i < local_size(dv); ++i)
        a[i] = a[i] / m[i] - damping * vp[i];
      du = v;
    }

    /// The tolerances' weighted RMS norm over the free entries.
    double
    scaled_norm(const std::vector<const VectorType *> &xu,
                const std::vector<const VectorType *> &xv,
                const State                           &y0,
                const VectorType                      *u1 = nullptr,
                const VectorType                      *v1 = nullptr) const
    {
      return tolerances.norm(xu, xv, free, y0.u, y0.v, u1, v1);
    }


    Attempt
    try_step(const State &state, const double step);

    void
    accept(State &state, const double step, StepReport &report);
  };
  RadauIIA::Attempt
  RadauIIA::try_step(const State &state, const double step)
  {
    Attempt      attempt;
    auto        &solid = context->solid;
    const double eps   = std::numeric_limits<double>::epsilon();
    const double t0    = state.time;
    const double c[3]  = {c1, c2, 1.};
    if (stiffness->assembled() && factorized_step != step)
      {
        systems->factorize(*stiffness, step);
        factorized_step = step;
      }

    // Starting values: the last step's collocation polynomial extended
    // (RADAU5; Jeffrey D.19, D.24-D.26 with ERRATA item 8), else zero.
    for (unsigned int i = 0; i < 3; ++i)
      {
        zu[i] = 0.;
        zv[i] = 0.;
        if (have_polynomial)
          {
            const double cq = c[i] * step / last_step;
            const double w0 = cq, w1 = cq * (cq - (c2 - 1.)),
                         w2 = w1 * (cq - (c1 - 1.));
            zu[i].add(w0, pu[0], w1, pu[1]);
            zu[i].add(w2, pu[2]);
            zv[i].add(w0, pv[0], w1, pv[1]);
            zv[i].add(w2, pv[2]);
          }
        // Prescribed entries: g(t0 + c_i h) - u0, and velocities that
        // make the stage polynomial interpolate them (V = A^-1 Z / h).
        VectorType stage(state.u);
        stage += zu[i];
        solid.apply_dirichlet_values(t0 + c[i] * step, stage);
        stage -= state.u;
        zu[i] = stage;
      }
    {
      const double *is_free = local_entries(free);
      const double *v0      = local_entries(state.v);
      for (unsigned int i = 0; i < 3; ++i)
        {
          double *zvp = local_entries(zv[i]);
          for (unsigned int k = 0; k < local_size(free); ++k)
            if (!(is_free[k] > 0))
              {
                double v = 0;
                for (unsigned int j = 0; j < 3; ++j)
                  v += inverse_a[i][j] * local_entries(zu[j])[k];
                zvp[k] = v / step - v0[k];
              }
        }
    }
    for (unsigned int i = 0; i < 3; ++i)
      {
        wu[i] = 0.;
        wv[i] = 0.;
        for (unsigned int j = 0; j < 3; ++j)
          {
            wu[i].add(TI[i][j], zu[j]);
            wv[i].add(TI[i][j], zv[j]);
          }
      }

    const double fnewt
      = std::max(10. * eps / tolerances.relative,
                 std::min(0.03, std::sqrt(tolerances.relative)));
    faccon                           = std::pow(std::max(faccon, eps), 0.8);
    theta                            = 1;
    double                    dynold = 0, thqold = 0;
    VectorType                u(state.u), v(state.v);
    std::array<VectorType, 3> ru, rv;
    for (unsigned int newt = 0; newt < max_newton; ++newt)
      {
        attempt.newton_iterations = newt + 1;
        try
          {
            for (unsigned int i = 0; i < 3; ++i)
              {
                u = state.u;
                u += zu[i];
                v = state.v;
                v += zv[i];
                derivative(t0 + c[i] * step, u, v, fu[i], fv[i]);
              }
          }
        catch (const SolverError &)
          {
            // An inverted element at a stage: a smaller step.
            attempt.next_step = 0.5 * step;
            return attempt;
          }
        // r = T^-1 F - Lambda W / h on the free entries.
        for (unsigned int i = 0; i < 3; ++i)
          {
            ru[i].reinit(state.u, false);
            rv[i].reinit(state.u, false);
            for (unsigned int j = 0; j < 3; ++j)
              {
                ru[i].add(TI[i][j], fu[j]);
                rv[i].add(TI[i][j], fv[j]);
              }
          }
        ru[0].add(-gamma_hat / step, wu[0]);
        rv[0].add(-gamma_hat / step, wv[0]);
        ru[1].add(-alpha_hat / step, wu[1], beta_hat / step, wu[2]);
        rv[1].add(-alpha_hat / step, wv[1], beta_hat / step, wv[2]);
        ru[2].add(-beta_hat / step, wu[1], -alpha_hat / step, wu[2]);
        rv[2].add(-beta_hat / step, wv[1], -alpha_hat / step, wv[2]);
        for (unsigned int i = 0; i < 3; ++i)
          {
            ru[i].scale(free);
            rv[i].scale(free);
          }
        systems->solve_real(step, ru[0], rv[0]);
        systems->solve_complex(step, ru[1], rv[1], ru[2], rv[2]);

        const double dyno = scaled_norm({&ru[0], &ru[1], &ru[2]},
                                        {&rv[0], &rv[1], &rv[2]},
                                        state);
        if (!std::isfinite(dyno))
          {
            attempt.next_step = 0.5 * step;
            return attempt;
          }
        if (newt >= 1)
          {
            const double thq = dyno / dynold;
            theta            = (newt == 1) ? thq : std::sqrt(thq * thqold);
            thqold           = thq;
            if (theta >= 0.99)
              {
                attempt.next_step = 0.5 * step;
                return attempt;
              }
            faccon = theta / (1. - theta);
            const double dyth
              = faccon * dyno * std::pow(theta, max_newton - 1. - newt) / fnewt;
            if (dyth >= 1.)
              {
                const double qnewt = std::max(1e-4, std::min(20., dyth));
                attempt.next_step
                  = 0.8 * std::pow(qnewt, -1. / (4. + max_newton - 1. - newt))
                    * step;
                return attempt;
              }
          }
        dynold = std::max(dyno, eps);
        for (unsigned int i = 0; i < 3; ++i)
          {
            wu[i] += ru[i];
            wv[i] += rv[i];
          }
        for (unsigned int i = 0; i < 3; ++i)
          {
            zu[i] = 0.;
            zv[i] = 0.;
            for (unsigned int j = 0; j < 3; ++j)
              {
                zu[i].add(T[i][j], wu[j]);
                zv[i].add(T[i][j], wv[j]);
              }
          }
        if (faccon * dyno <= fnewt)
          {
            attempt.converged = true;
            break;
          }
      }
    if (!attempt.converged)
      {
        attempt.next_step = 0.5 * step;
        return attempt;
      }

    // Error estimate (D.21-D.22): (gamma_hat/h I - J)^-1 (f0 + sum dd_i
    // Z_i / h).
    VectorType eu(f0u), ev(f0v);
    eu.add(dd1 / step, zu[0], dd2 / step, zu[1]);
    eu.add(dd3 / step, zu[2]);
    ev.add(dd1 / step, zv[0], dd2 / step, zv[1]);
    ev.add(dd3 / step, zv[2]);
    eu.scale(free);
    ev.scale(free);
    systems->solve_real(step, eu, ev);
    VectorType u1(state.u), v1(state.v);
    u1 += zu[2];
    v1 += zv[2];
    attempt.error = std::max(scaled_norm({&eu}, {&ev}, state, &u1, &v1), 1e-10);
    // RADAU5's step control: a safety factor that shrinks with the Newton
    // iterations used, h changing by a factor within [1/5, 8].
    const double fac
      = std::min(0.9,
                 0.9 * (1. + 2. * max_newton)
                   / (attempt.newton_iterations + 2. * max_newton));
    const double quot
      = std::max(1. / 8., std::min(5., std::pow(attempt.error, 0.25) / fac));
    attempt.next_step = step / quot;
    // Keep h (and the factorization) when it would grow by less than 20 %.
    if (attempt.error < 1. && theta <= 1e-3 && attempt.next_step >= step
        && attempt.next_step <= 1.2 * step)
      attempt.next_step = step;
    return attempt;
  }


  void
  RadauIIA::accept(State &state, const double step, StepReport &report)
  {
    // Energy taken out by the damping force, c int v^T M v dt, by the
    // method's own quadrature (weights b_i = a_3i).
    if (damping > 0)
      {
        const double *m = local_entries(*mass), *v0 = local_entries(state.v);
        const double  b[3] = {b1, b2, b3};
        double        work = 0;
        for (unsigned int i = 0; i < 3; ++i)
          {
            const double *z = local_entries(zv[i]);
            for (unsigned int k = 0; k < local_size(state.v); ++k)
              work += b[i] * m[k] * std::pow(v0[k] + z[k], 2);
          }
        report.damping_work
          += damping * step
             * Utilities::MPI::sum(work, parallel_tools::communicator());
      }
    // The collocation polynomial in Newton's form for the next starting
    // values (RADAU5's CONT; ERRATA item 8 corrects D.26's divisor).
    for (auto [z, p] : {std::make_pair(&zu, &pu), std::make_pair(&zv, &pv)})
      {
        auto      &Z = *z;
        auto      &P = *p;
        VectorType ak(Z[0]), acont3(Z[0]);
        P[0] = Z[1];
        P[0] -= Z[2];
        P[0] /= (c2 - 1.);
        ak -= Z[1];
        ak /= (c1 - c2);
        acont3 /= c1;
        acont3.sadd(-1. / c2, 1. / c2, ak);
        P[1] = ak;
        P[1] -= P[0];
        P[1] /= (c1 - 1.);
        P[2] = P[1];
        P[2] -= acont3;
      }
    have_polynomial = true;
    last_step       = step;
    state.u += zu[2];
    state.v += zv[2];
    state.time += step;
    derivative(state.time, state.u, state.v, f0u, f0v);
    state.a = f0v;
    // RADAU5 keeps the Jacobian while Newton contracts fast.
    jacobian_fresh   = false;
    jacobian_current = theta <= 1e-3;
  }

  TISSUEFEM_REGISTER_INTEGRATOR(
    RadauIIA,
    "radau iia",
    "the 3-stage Radau IIA implicit Runge-Kutta method (order 5, adaptive "
    "step; Jeffrey appendix D) with lumped mass and mass-proportional "
    "damping; analytical, numerical or simplified Jacobian.")
} // namespace tissuefem::time
