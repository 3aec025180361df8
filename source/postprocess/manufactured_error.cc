#include <tissuefem/adaptation/stress_jump.h>
#include <tissuefem/output/checkpoint.h>
#include <tissuefem/postprocess/manufactured_error.h>

#include <cmath>

namespace tissuefem::postprocess
{
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
    const auto e = manufactured->errors(*this->context->scene.discretization,
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

  template class ManufacturedError<1>;
  template class ManufacturedError<2>;
  template class ManufacturedError<3>;

  TISSUEFEM_REGISTER_POSTPROCESSOR(
    ManufacturedError,
    "manufactured error",
    "with a manufactured solution: the L2 and H1 errors per step and over "
    "the run, and the error estimate's effectivity, in run.txt.")
} // namespace tissuefem::postprocess
