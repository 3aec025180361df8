// A scene for unit tests: the scene a run builds from the parameters
// (Scene: mesh, materials, boundary conditions, solid) and the
// solvers an integrator needs, so that a test can drive the solid and
// integrators itself.
#pragma once

#include <deal.II/base/parameter_handler.h>

#include <tissuefem/adaptation/mesh_adaptation.h>
#include <tissuefem/scene/scene.h>
#include <tissuefem/solvers/linear_solver.h>
#include <tissuefem/solvers/newton.h>
#include <tissuefem/time/interface.h>

#include <cmath>
#include <memory>
#include <string>

#include "../tests.h"

namespace tissuefem_tests
{
  using namespace dealii;
  using namespace tissuefem;

  template <int dim>
  struct SolidScene : public Scene<dim>
  {
    explicit SolidScene(ParameterHandler &prm)
        : Scene<dim>(prm)
    {
      time_parameters.parse_parameters(prm);
      newton_parameters.parse_parameters(prm);
      linear_solver = std::make_unique<solvers::LinearSolver>(prm);
    }

    /// What an integrator drives: this scene's solid, time and Newton
    /// parameters and linear solver.
    time::Context
    context()
    {
      return {*this->solid, time_parameters, newton_parameters, *linear_solver};
    }

    /// The integrator 'Time integration/Integrator' names.
    std::unique_ptr<time::Interface>
    integrator(ParameterHandler &prm) const
    {
      return time::IntegratorRegistry::instance().create(
        time_parameters.integrator, prm);
    }

    /// A run of the scene from its initial state, with the integrator
    /// initialized (which keeps a pointer to the context: a Run stays where
    /// start() made it).
    struct Run
    {
      time::Context                    context;
      std::unique_ptr<time::Interface> integrator;
      time::State                      state;

      /// Steps until @p end_time.
      void
      advance_to(const double end_time)
      {
        while (state.time < end_time - 1e-9 * std::max(1., std::abs(end_time)))
          integrator->advance(state, end_time);
      }
    };

    /// Adaptation of this scene's mesh and solid as 'Mesh refinement' says.
    std::unique_ptr<adaptation::MeshAdaptation<dim>>
    mesh_adaptation(ParameterHandler &prm)
    {
      adaptation::MeshRefinementParameters refinement;
      refinement.parse_parameters(prm);
      return std::make_unique<adaptation::MeshAdaptation<dim>>(
        refinement, this->triangulation, *this->solid);
    }

    /// Starts a run of 'Time integration/Integrator' from the initial state.
    std::unique_ptr<Run>
    start(ParameterHandler &prm)
    {
      auto run = std::unique_ptr<Run>(new Run{context(), integrator(prm), {}});
      this->solid->initial_state(run->state.u, run->state.v);
      run->integrator->initialize(run->context, run->state);
      return run;
    }

    time::TimeParameters                   time_parameters;
    solvers::NewtonParameters              newton_parameters;
    std::unique_ptr<solvers::LinearSolver> linear_solver;
  };


  /**
   * Central differences of step h = 1e-6 along @p d at @p u: checks that
   * the residual of implicit_residual(u, u_tilde, c, t) is the derivative
   * of implicit_energy() along d, and (unless @p jacobian is false: a
   * projected tangent is no derivative) that the Jacobian times d is the
   * residual's, both relatively below 1e-6. Leaves the Jacobian of u
   * assembled.
   */
  template <int dim>
  void
  check_derivatives(solid::Solid<dim> &solid,
                    const VectorType  &u,
                    const VectorType  &u_tilde,
                    const double       c,
                    const double       t,
                    const VectorType  &d,
                    const std::string &name,
                    const bool         jacobian = true)
  {
    const double h = 1e-6;
    VectorType   r, r_plus, r_minus, Jd(u);
    solid.implicit_residual(u, u_tilde, c, t, r, true);
    solid.jacobian().vmult(Jd, d);
    VectorType x(u);
    x.add(h, d);
    const double e_plus = solid.implicit_energy(x, u_tilde, c, t);
    solid.implicit_residual(x, u_tilde, c, t, r_plus, false);
    x.add(-2 * h, d);
    const double e_minus = solid.implicit_energy(x, u_tilde, c, t);
    solid.implicit_residual(x, u_tilde, c, t, r_minus, false);
    const double slope = r * d;
    check_small(std::abs((e_plus - e_minus) / (2 * h) - slope)
                  / std::abs(slope),
                1e-6,
                name + ": residual . d against dE/dd");
    if (!jacobian)
      return;
    r_plus -= r_minus;
    r_plus /= 2 * h;
    r_plus -= Jd;
    check_small(r_plus.l2_norm() / Jd.l2_norm(),
                1e-6,
                name + ": J d against dR/dd");
  }


  /**
   * The single degree of freedom of the order tests: a 1D bar (0, 1) of
   * one linear element, clamped at x = 0, linear elastic with E = 1, nu =
   * 0, rho = 1 (so k = 1; lumped mass 1/2, consistent 1/3), started from u
   * = 0.01 x at rest. @p time_integration is the body of the 'Time
   * integration' subsection.
   */
  inline std::string
  one_element_bar(const std::string &time_integration)
  {
    return R"(
    set Dimension = 1
    subsection Geometry
      set Lower corner = 0
      set Upper corner = 1
      set Subdivisions = 1
    end
    subsection Materials
      set Model = linear elastic
      set Young's modulus = 1
      set Poisson's ratio = 0
      set Density = 1
    end
    subsection Boundary conditions
      set Dirichlet = 0: x: 0
      set Initial displacement = 0.01*x
    end
    subsection Time integration
)" + time_integration
           + "\n    end\n";
  }


  /// u(1) of backward Euler on the one-element bar's m u'' + u = 0 (k = 1)
  /// from u = 0.01 at rest in @p steps steps of 1/steps: the recursion
  /// (m + h^2) v_{n+1} = m v_n - h u_n, u_{n+1} = u_n + h v_{n+1}, with
  /// @p m the bar's mass (1/3 consistent, 1/2 lumped).
  inline double
  one_element_bar_backward_euler(const double m, const unsigned int steps = 50)
  {
    double       u = 0.01, v = 0;
    const double h = 1. / steps;
    for (unsigned int n = 0; n < steps; ++n)
      {
        v = (m * v - h * u) / (m + h * h);
        u += h * v;
      }
    return u;
  }


  /// Builds the scene of @p prm with 'Time step' @p step and 'End time'
  /// @p end_time, runs its integrator from the initial state to the end and
  /// returns the largest |u| (the single free node's displacement in the
  /// order tests); the final displacement and the integrator's summary()
  /// go to @p final_u and @p summary if given.
  template <int dim>
  double
  run_to_end(ParameterHandler &prm,
             const double      step,
             const double      end_time,
             Vector<double>   *final_u = nullptr,
             std::string      *summary = nullptr)
  {
    prm.enter_subsection("Time integration");
    prm.set("Time step", step);
    prm.set("End time", end_time);
    prm.leave_subsection();
    SolidScene<dim> scene(prm);
    auto           &solid      = *scene.solid;
    time::Context   context    = scene.context();
    auto            integrator = scene.integrator(prm);
    time::State     state;
    solid.initial_state(state.u, state.v);
    solid.apply_dirichlet_values(0., state.u);
    integrator->initialize(context, state);
    while (state.time < end_time * (1 - 1e-12))
      integrator->advance(state, end_time);
    if (final_u)
      *final_u = Vector<double>(state.u);
    if (summary)
      *summary = integrator->summary();
    return state.u.linfty_norm();
  }
} // namespace tissuefem_tests
