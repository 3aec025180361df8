#include <tissuefem/output/output_files.h>
#include <tissuefem/postprocess/tool_force.h>

#include <iomanip>
#include <sstream>

namespace tissuefem::postprocess
{
  template <int dim>
  std::vector<std::string>
  ToolForce<dim>::files() const
  {
    if (!this->context->scene.tool)
      return {};
    return {this->context->directory + "/tool_force.csv",
            this->context->directory + "/haptic_force.csv"};
  }


  template <int dim>
  void
  ToolForce<dim>::open()
  {
    auto &tool = this->context->scene.tool;
    if (!tool)
      return;
    // Every process takes part in a device link (it shares the positions).
    tool->connect(this->context->directory);
    if (!parallel_tools::is_root())
      return;
    const char *names[3] = {"x", "y", "z"};
    output::create_file(force_file, files()[0]);
    output::create_file(haptic_file, files()[1]);
    force_file << "time,holding";
    for (unsigned int d = 0; d < dim; ++d)
      force_file << ",tool_" << names[d];
    for (unsigned int d = 0; d < dim; ++d)
      force_file << ",force_" << names[d];
    force_file << '\n' << std::flush;
    haptic_file << "time";
    for (unsigned int d = 0; d < dim; ++d)
      haptic_file << ",force_" << names[d];
    haptic_file << ",error\n" << std::flush;
  }


  template <int dim>
  void
  ToolForce<dim>::restore(const std::vector<std::string> &)
  {
    if (!this->context->scene.tool || !parallel_tools::is_root())
      return;
    output::append_to_file(force_file, files()[0]);
    output::append_to_file(haptic_file, files()[1]);
  }


  template <int dim>
  void
  ToolForce<dim>::execute(const Step &step)
  {
    auto &tool = this->context->scene.tool;
    if (!tool)
      return;
    const tool::Record<dim> record
      = tool->record(step.state, *this->context->scene.solid);
    this->context->summary.line(
      output::vector_line(step.state.time, "tool force", record.force, dim));
    if (!parallel_tools::is_root())
      return;
    for (const auto &sample : record.haptic)
      {
        haptic_file << sample.time;
        for (unsigned int d = 0; d < dim; ++d)
          haptic_file << ',' << sample.force[d];
        haptic_file << ',' << sample.error << '\n';
      }
    haptic_file << std::flush;
    force_file << step.state.time << ',' << (record.engaged ? 1 : 0);
    for (unsigned int d = 0; d < dim; ++d)
      force_file << ',' << record.position[d];
    for (unsigned int d = 0; d < dim; ++d)
      force_file << ',' << record.force[d];
    force_file << '\n' << std::flush;
  }


  template <int dim>
  void
  ToolForce<dim>::finish(const time::State &,
                         const RunTotals &,
                         output::RunRecord &)
  {
    if (auto &tool = this->context->scene.tool)
      parallel_tools::screen() << tool->summary() << std::endl;
  }

  template class ToolForce<1>;
  template class ToolForce<2>;
  template class ToolForce<3>;

  TISSUEFEM_REGISTER_POSTPROCESSOR(
    ToolForce,
    "tool force",
    "with a tool: tool_force.csv (the force on it every step), "
    "haptic_force.csv (the forces sent to a haptic device between steps) "
    "and the haptic report.")
} // namespace tissuefem::postprocess
