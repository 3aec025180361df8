#include <tissuefem/postprocess/tool_force.h>

#include <iomanip>
#include <sstream>

namespace tissuefem::postprocess
{
  template <int dim>
  void
  ToolForce<dim>::initialize(const Context<dim> &c)
  {
    context = &c;
  }


  template <int dim>
  void
  ToolForce<dim>::open()
  {
    if (auto &tool = context->scene.tool)
      tool->open(context->directory);
  }


  template <int dim>
  void
  ToolForce<dim>::execute(const Step &step)
  {
    auto &tool = context->scene.tool;
    if (!tool)
      return;
    const Tensor<1, dim> force
      = tool->record(step.state, *context->scene.solid);
    std::ostringstream line;
    line << std::setprecision(8) << "t = " << step.state.time
         << " tool force =";
    for (unsigned int d = 0; d < dim; ++d)
      line << ' ' << force[d];
    context->summary.line(line.str());
  }


  template <int dim>
  void
  ToolForce<dim>::finish(const time::State &,
                         const RunTotals &,
                         output::RunRecord &)
  {
    if (auto &tool = context->scene.tool)
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
