#include <tissuefem/postprocess/tool_force.h>

#include <iomanip>
#include <sstream>

namespace tissuefem::postprocess
{
  template <int dim>
  void
  ToolForce<dim>::open()
  {
    if (auto &tool = this->context->scene.tool)
      tool->open(this->context->directory);
  }


  template <int dim>
  void
  ToolForce<dim>::execute(const Step &step)
  {
    auto &tool = this->context->scene.tool;
    if (!tool)
      return;
    const Tensor<1, dim> force
      = tool->record(step.state, *this->context->scene.solid);
    this->context->summary.line(
      output::vector_line(step.state.time, "tool force", force, dim));
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
    "with a tool: the force on it every step (tool_force.csv), the haptic "
    "stream (haptic_force.csv) and the haptic report.")
} // namespace tissuefem::postprocess
