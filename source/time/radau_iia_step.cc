#include <deal.II/base/tensor.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/time/nodal.h>
#include <tissuefem/time/radau_iia.h>

#include <array>
#include <cmath>
#include <limits>

// The Runge-Kutta step of Radau IIA (the class is documented in
// radau_iia.h; its parameters and the loop over an interval are in
// radau_iia.cc): starting values, the simplified Newton iteration on the
// stage equations, the error estimate and the accepted step.
namespace tissuefem::time
{
  namespace
  {
    // The 3-stage Radau IIA method (Hairer and Wanner, Solving ODEs II,
    // IV.5 and their code RADAU5; Jeffrey appendix D with erratum J8,
    // doc/references.md): nodes c, and the transformation T with T^-1 A^-1 T =
    // [gamma 0 0; 0 alpha -beta; 0 beta alpha].
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
    // The error estimate's weights (erratum J8, doc/references.md, D.22, times
    // gamma_hat).
    const double dd1 = -(13. + 7. * s6) / 3., dd2 = (-13. + 7. * s6) / 3.,
                 dd3 = -1. / 3.;
    // Quadrature weights b_i = a_3i.
    const double b1 = (16. - s6) / 36., b2 = (16. + s6) / 36., b3 = 1. / 9.;
    // The stage nodes c_i, as fractions of the step.
    const double stage_nodes[3] = {c1, c2, 1.};
  } // namespace

  void
  RadauIIA::set_up_vectors(const VectorType &like)
  {
    system->reinit(context->solid, like);
    for (auto *set : {&zu, &zv, &wu, &wv, &fu, &fv, &pu, &pv})
      for (auto &v : *set)
        v.reinit(like, false);
    f0u.reinit(like, false);
    f0v.reinit(like, false);
    if (!systems)
      systems = std::make_unique<RadauLinearSystems>(system->damping(),
                                                     gamma_hat,
                                                     alpha_hat,
                                                     beta_hat);
    systems->reinit(system->mass(),
                    system->free(),
                    stiffness->assembled(),
                    context->linear_solver);
  }


  void
  RadauIIA::derivative(const double      t,
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
    const double *m = local_entries(system->mass()), *vp = local_entries(v);
    const double  damping = system->damping();
    for (unsigned int i = 0; i < local_size(dv); ++i)
      a[i] = a[i] / m[i] - damping * vp[i];
    du = v;
  }


  RadauIIA::Attempt
  RadauIIA::try_step(const State &state, const double step)
  {
    Attempt attempt;
    start_stages(state, step);
    if (!solve_stages(state, step, attempt))
      return attempt;
    estimate_error(state, step, attempt);
    return attempt;
  }


  void
  RadauIIA::start_stages(const State &state, const double step)
  {
    if (stiffness->assembled() && factorized_step != step)
      {
        systems->factorize(*stiffness, step);
        factorized_step = step;
      }

    // Starting values: the last step's collocation polynomial extended
    // (RADAU5; Jeffrey D.19, D.24-D.26 with erratum J8, doc/references.md),
    // else zero.
    for (unsigned int i = 0; i < 3; ++i)
      {
        zu[i] = 0.;
        zv[i] = 0.;
        if (have_polynomial)
          {
            const double cq = stage_nodes[i] * step / last_step;
            const double w0 = cq, w1 = cq * (cq - (c2 - 1.)),
                         w2 = w1 * (cq - (c1 - 1.));
            zu[i].add(w0, pu[0], w1, pu[1]);
            zu[i].add(w2, pu[2]);
            zv[i].add(w0, pv[0], w1, pv[1]);
            zv[i].add(w2, pv[2]);
          }
        // Prescribed entries: g(t0 + c_i h) - u0.
        VectorType stage(state.u);
        stage += zu[i];
        context->solid.apply_dirichlet_values(state.time
                                                + stage_nodes[i] * step,
                                              stage);
        stage -= state.u;
        zu[i] = stage;
      }
    set_boundary_velocities(state, step);
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
  }


  void
  RadauIIA::set_boundary_velocities(const State &state, const double step)
  {
    const double *is_free = local_entries(system->free());
    const double *v0      = local_entries(state.v);
    for (unsigned int i = 0; i < 3; ++i)
      {
        double *zvp = local_entries(zv[i]);
        for (unsigned int k = 0; k < local_size(system->free()); ++k)
          if (!(is_free[k] > 0))
            {
              double v = 0;
              for (unsigned int j = 0; j < 3; ++j)
                v += inverse_a[i][j] * local_entries(zu[j])[k];
              zvp[k] = v / step - v0[k];
            }
      }
  }


  bool
  RadauIIA::solve_stages(const State &state,
                         const double step,
                         Attempt     &attempt)
  {
    const double eps = std::numeric_limits<double>::epsilon();
    const double fnewt
      = std::max(10. * eps / tolerances.relative,
                 std::min(0.03, std::sqrt(tolerances.relative)));
    faccon                           = std::pow(std::max(faccon, eps), 0.8);
    theta                            = 1;
    double                    dynold = 0, thqold = 0;
    std::array<VectorType, 3> ru, rv;
    // Every way out but convergence retries with half the step, except a
    // slow predicted convergence, which picks its own step below.
    attempt.next_step = 0.5 * step;
    for (unsigned int newt = 0; newt < max_newton; ++newt)
      {
        attempt.newton_iterations = newt + 1;
        if (!evaluate_stages(state, step))
          return false;
        newton_increments(state, step, ru, rv);
        const double dyno = scaled_norm({&ru[0], &ru[1], &ru[2]},
                                        {&rv[0], &rv[1], &rv[2]},
                                        state);
        if (!std::isfinite(dyno))
          return false;
        // RADAU5's contraction test: give up when Newton diverges or would
        // not reach the tolerance within the iterations left.
        if (newt >= 1)
          {
            const double thq = dyno / dynold;
            theta            = (newt == 1) ? thq : std::sqrt(thq * thqold);
            thqold           = thq;
            if (theta >= 0.99)
              return false;
            faccon = theta / (1. - theta);
            const double dyth
              = faccon * dyno * std::pow(theta, max_newton - 1. - newt) / fnewt;
            if (dyth >= 1.)
              {
                const double qnewt = std::max(1e-4, std::min(20., dyth));
                attempt.next_step
                  = 0.8 * std::pow(qnewt, -1. / (4. + max_newton - 1. - newt))
                    * step;
                return false;
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
            return true;
          }
      }
    return false;
  }


  bool
  RadauIIA::evaluate_stages(const State &state, const double step)
  {
    VectorType u(state.u), v(state.v);
    try
      {
        for (unsigned int i = 0; i < 3; ++i)
          {
            u = state.u;
            u += zu[i];
            v = state.v;
            v += zv[i];
            derivative(state.time + stage_nodes[i] * step, u, v, fu[i], fv[i]);
          }
      }
    catch (const SolverError &)
      {
        // An inverted element at a stage: the caller retries a smaller step.
        return false;
      }
    return true;
  }


  void
  RadauIIA::newton_increments(const State               &state,
                              const double               step,
                              std::array<VectorType, 3> &ru,
                              std::array<VectorType, 3> &rv)
  {
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
        ru[i].scale(system->free());
        rv[i].scale(system->free());
      }
    systems->solve_real(step, ru[0], rv[0]);
    systems->solve_complex(step, ru[1], rv[1], ru[2], rv[2]);
  }


  void
  RadauIIA::estimate_error(const State &state,
                           const double step,
                           Attempt     &attempt)
  {
    // Error estimate (D.21-D.22): (gamma_hat/h I - J)^-1 (f0 + sum dd_i
    // Z_i / h).
    VectorType eu(f0u), ev(f0v);
    eu.add(dd1 / step, zu[0], dd2 / step, zu[1]);
    eu.add(dd3 / step, zu[2]);
    ev.add(dd1 / step, zv[0], dd2 / step, zv[1]);
    ev.add(dd3 / step, zv[2]);
    eu.scale(system->free());
    ev.scale(system->free());
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
  }


  void
  RadauIIA::accept(State &state, const double step, StepReport &report)
  {
    // Energy taken out by the damping force, c int v^T M v dt, by the
    // method's own quadrature (weights b_i = a_3i).
    const double damping = system->damping();
    if (damping > 0)
      {
        const double *m   = local_entries(system->mass()),
                     *v0  = local_entries(state.v);
        const double b[3] = {b1, b2, b3};
        double       work = 0;
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
    // values (RADAU5's CONT; erratum J8, doc/references.md corrects D.26's
    // divisor).
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
} // namespace tissuefem::time
