#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <tissuefem/adaptation/stress_jump.h>
#include <tissuefem/output/checkpoint.h>
#include <tissuefem/postprocess/manufactured_error.h>

#include <cmath>

namespace tissuefem::postprocess
{
  template <int dim>
  ManufacturedErrors
  manufactured_errors(const boundary::ManufacturedSolution<dim> &exact,
                      const solid::Discretization<dim>          &discretization,
                      const VectorType                          &u_ghosted,
                      const double                               t)
  {
    // Two more points per direction than the element needs, so that the
    // quadrature error stays below the discretization error.
    // (deal.II's simplex Gauss rules stop at 4 points per direction.)
    const unsigned int    n_points = discretization.fe->degree + 3;
    const Quadrature<dim> quadrature
      = discretization.simplex
          ? Quadrature<dim>(QGaussSimplex<dim>(std::min(n_points, 4u)))
          : Quadrature<dim>(QGauss<dim>(n_points));
    FEValues<dim>                    fe_values(*discretization.mapping,
                            *discretization.fe,
                            quadrature,
                            update_values | update_gradients
                              | update_quadrature_points | update_JxW_values);
    const FEValuesExtractors::Vector displacement_extractor(0);
    std::vector<Tensor<1, dim>>      u_h(quadrature.size());
    std::vector<Tensor<2, dim>>      grad_u_h(quadrature.size());
    double                           sums[4] = {0, 0, 0, 0};
    for (const auto &cell : discretization.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[displacement_extractor].get_function_values(u_ghosted, u_h);
          fe_values[displacement_extractor].get_function_gradients(u_ghosted,
                                                                   grad_u_h);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              const Point<dim>    &X  = fe_values.quadrature_point(q);
              const Tensor<1, dim> u  = exact.displacement(X, t);
              const Tensor<2, dim> G  = exact.gradient(X, t);
              const double         dx = fe_values.JxW(q);
              sums[0] += (u_h[q] - u).norm_square() * dx;
              sums[1] += (grad_u_h[q] - G).norm_square() * dx;
              sums[2] += u.norm_square() * dx;
              sums[3] += G.norm_square() * dx;
            }
        }
    Utilities::MPI::sum(ArrayView<const double>(sums, 4),
                        parallel_tools::communicator(),
                        ArrayView<double>(sums, 4));
    return {std::sqrt(sums[0]),
            std::sqrt(sums[1]),
            std::sqrt(sums[2]),
            std::sqrt(sums[3])};
  }


  template <int dim>
  std::vector<std::string>
  ManufacturedError<dim>::save() const
  {
    std::vector<std::string> lines;
    for (const double x : {max_l2,
                           l2_time_integral,
                           last_time,
                           last.l2,
                           last.h1,
                           last.l2_exact,
                           last.h1_exact})
      lines.push_back(output::exact_text(x));
    return lines;
  }


  template <int dim>
  void
  ManufacturedError<dim>::restore(const std::vector<std::string> &lines)
  {
    if (lines.size() != 7)
      return;
    double *targets[] = {&max_l2,
                         &l2_time_integral,
                         &last_time,
                         &last.l2,
                         &last.h1,
                         &last.l2_exact,
                         &last.h1_exact};
    for (unsigned int i = 0; i < 7; ++i)
      *targets[i] = output::exact_value(lines[i]);
  }


  template <int dim>
  void
  ManufacturedError<dim>::execute(const Step<dim> &step)
  {
    const auto &manufactured = this->context->scene.manufactured;
    if (!manufactured)
      return;
    const auto e = manufactured_errors(*manufactured,
                                       *this->context->scene.discretization,
                                       step.u_ghosted,
                                       step.state.time);
    max_l2       = std::max(max_l2, e.l2);
    // Rectangle rule on the step just taken: sum over steps of dt e^2.
    l2_time_integral += (step.state.time - last_time) * e.l2 * e.l2;
    last_time = step.state.time;
    last      = e;
  }


  template <int dim>
  void
  ManufacturedError<dim>::finish(const time::State &state,
                                 const RunTotals &,
                                 output::RunRecord &r)
  {
    const auto &scene = this->context->scene;
    if (!scene.manufactured)
      return;
    parallel_tools::screen()
      << "error against the manufactured solution at t = " << state.time
      << ": L2 " << last.l2 << " (length units; relative "
      << last.l2 / last.l2_exact << "), H1 seminorm " << last.h1
      << " (relative " << last.h1 / last.h1_exact << "); largest L2 error "
      << "over the steps " << max_l2 << std::endl;
    // The estimator's effectivity where the true error is known (hypercube
    // meshes: the estimator evaluates neighbours by their reference
    // coordinates).
    double estimate = -1;
    if (!scene.discretization->simplex)
      {
        VectorType u;
        scene.discretization->initialize_vector(u, true);
        u = state.u;
        estimate
          = adaptation::stress_jump_estimate(*scene.solid, u, state.time);
      }
    r.add("L2 error", last.l2, "length units, ||u_h - u||_L2 at the end");
    r.add("H1 error",
          last.h1,
          "||Grad(u_h - u)||_L2 at the end (length^(dim/2))");
    r.add("relative L2 error",
          last.l2 / last.l2_exact,
          "||u_h - u||/||u|| at the end");
    r.add("relative H1 error",
          last.h1 / last.h1_exact,
          "||Grad(u_h - u)||/||Grad u|| at the end");
    r.add("max L2 error", max_l2, "length units, largest over the steps");
    r.add("L2L2 error",
          std::sqrt(l2_time_integral),
          "(sum over steps of dt ||u_h - u||_L2^2)^(1/2)");
    if (estimate >= 0)
      {
        r.add("error estimate",
              estimate,
              "stress-jump estimate of the H1 seminorm error at the end");
        r.add("effectivity",
              estimate / last.h1,
              "error estimate / H1 error (1: exact estimate)");
      }
  }

  template ManufacturedErrors
  manufactured_errors(const boundary::ManufacturedSolution<1> &,
                      const solid::Discretization<1> &,
                      const VectorType &,
                      double);
  template ManufacturedErrors
  manufactured_errors(const boundary::ManufacturedSolution<2> &,
                      const solid::Discretization<2> &,
                      const VectorType &,
                      double);
  template ManufacturedErrors
  manufactured_errors(const boundary::ManufacturedSolution<3> &,
                      const solid::Discretization<3> &,
                      const VectorType &,
                      double);

  template class ManufacturedError<1>;
  template class ManufacturedError<2>;
  template class ManufacturedError<3>;

  TISSUEFEM_REGISTER_POSTPROCESSOR(
    ManufacturedError,
    "manufactured error",
    "with a manufactured solution: the L2 and H1 errors per step and over "
    "the run, and the error estimate's effectivity, in run.txt.")
} // namespace tissuefem::postprocess
