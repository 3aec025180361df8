#include <tissuefem/output/checkpoint.h>
#include <tissuefem/output/output_files.h>
#include <tissuefem/postprocess/statistics.h>

namespace tissuefem::postprocess
{
  template <int dim>
  std::vector<std::string>
  Statistics<dim>::files() const
  {
    return {this->context->directory + "/statistics.csv"};
  }


  template <int dim>
  void
  Statistics<dim>::open()
  {
    if (!parallel_tools::is_root())
      return;
    output::create_file(file, files()[0]);
    file << "step,time,dt,newton_iterations,linear_iterations,"
            "rejected_attempts,final_residual_norm,assembly_seconds,"
            "solve_seconds,step_seconds,substeps,jacobian_evaluations,"
            "stored_energy,kinetic_energy,damping_work,multiplier_updates,"
            "contact_seconds\n";
  }


  template <int dim>
  std::vector<std::string>
  Statistics<dim>::save() const
  {
    return {output::exact_text(damping_work)};
  }


  template <int dim>
  void
  Statistics<dim>::restore(const std::vector<std::string> &lines)
  {
    damping_work = lines.empty() ? 0. : output::exact_value(lines[0]);
    if (parallel_tools::is_root())
      output::append_to_file(file, files()[0]);
  }


  template <int dim>
  void
  Statistics<dim>::execute(const Step<dim> &step)
  {
    if (step.number == 0)
      return;
    // The energies are collective; every process computes them.
    auto        &solid   = *this->context->scene.solid;
    const double stored  = solid.stored_energy(step.state.u);
    const double kinetic = solid.kinetic_energy(step.state.v);
    const auto  &s       = step.report;
    damping_work += s.damping_work;
    if (!parallel_tools::is_root())
      return;
    file << step.number << ',' << step.state.time << ',' << s.dt << ','
         << s.newton_iterations << ',' << s.linear_iterations << ','
         << s.rejected_attempts << ',' << s.residual_norm << ','
         << s.assembly_seconds << ',' << s.solve_seconds << ','
         << s.step_seconds << ',' << s.substeps << ',' << s.jacobian_evaluations
         << ',' << stored << ',' << kinetic << ',' << damping_work << ','
         << s.multiplier_updates << ',' << s.contact_seconds << std::endl;
  }

  template class Statistics<1>;
  template class Statistics<2>;
  template class Statistics<3>;

  TISSUEFEM_REGISTER_POSTPROCESSOR(
    Statistics,
    "statistics",
    "statistics.csv: per step, time, step size, iterations, wall times, "
    "energies, damping work, contact multiplier updates and the wall time "
    "spent in contact.")
} // namespace tissuefem::postprocess
