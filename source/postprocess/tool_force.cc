#include <tissuefem/output/output_files.h>
#include <tissuefem/postprocess/tool_force.h>

#include <algorithm>
#include <iomanip>
#include <sstream>

namespace tissuefem::postprocess
{
  namespace
  {
    /// A name fit for a file name: spaces become '_'.
    std::string
    file_part(std::string name)
    {
      std::replace(name.begin(), name.end(), ' ', '_');
      return name;
    }
  } // namespace


  template <int dim>
  std::vector<std::string>
  ToolForce<dim>::files() const
  {
    // One tool keeps the plain names; several name theirs.
    const auto              &tools = this->context->scene.tools;
    std::vector<std::string> result;
    for (const auto &[name, tool] : tools)
      {
        const std::string suffix
          = tools.size() == 1 ? "" : "-" + file_part(name);
        result.push_back(this->context->directory + "/tool_force" + suffix
                         + ".csv");
        result.push_back(this->context->directory + "/haptic_force" + suffix
                         + ".csv");
      }
    return result;
  }


  template <int dim>
  void
  ToolForce<dim>::open()
  {
    const auto &tools = this->context->scene.tools;
    // Every process takes part in a device link (it shares the positions).
    // What a device may ask is scaled by the body's diameter.
    for (const auto &[name, tool] : tools)
      tool->connect(this->context->directory,
                    this->context->scene.solid->length_scale());
    if (!parallel_tools::is_root())
      return;
    const std::vector<std::string> names = files();
    streams.resize(names.size());
    const char *axes[3] = {"x", "y", "z"};
    for (unsigned int i = 0; i < names.size(); i += 2)
      {
        std::ofstream &force = streams[i], &haptic = streams[i + 1];
        output::create_file(force, names[i]);
        output::create_file(haptic, names[i + 1]);
        force << "time,holding";
        for (unsigned int d = 0; d < dim; ++d)
          force << ",tool_" << axes[d];
        for (unsigned int d = 0; d < dim; ++d)
          force << ",force_" << axes[d];
        force << '\n' << std::flush;
        haptic << "time";
        for (unsigned int d = 0; d < dim; ++d)
          haptic << ",force_" << axes[d];
        haptic << ",error\n" << std::flush;
      }
  }


  template <int dim>
  void
  ToolForce<dim>::restore(const std::vector<std::string> &)
  {
    if (!parallel_tools::is_root())
      return;
    const std::vector<std::string> names = files();
    streams.resize(names.size());
    for (unsigned int i = 0; i < names.size(); ++i)
      output::append_to_file(streams[i], names[i]);
  }


  template <int dim>
  void
  ToolForce<dim>::execute(const Step<dim> &step)
  {
    const auto  &tools = this->context->scene.tools;
    unsigned int i     = 0;
    for (const auto &[name, tool] : tools)
      {
        const tool::Record<dim> record
          = tool->record(step.state, *this->context->scene.solid, step.contact);
        const std::string label
          = tools.size() == 1 ? "tool force" : "tool force (" + name + ")";
        this->context->summary.line(
          output::vector_line(step.state.time, label, record.force, dim));
        if (parallel_tools::is_root())
          write(record, step.state.time, streams[i], streams[i + 1]);
        i += 2;
      }
  }


  template <int dim>
  void
  ToolForce<dim>::write(const tool::Record<dim> &record,
                        const double             time,
                        std::ofstream           &force,
                        std::ofstream           &haptic)
  {
    for (const auto &sample : record.haptic)
      {
        haptic << sample.time;
        for (unsigned int d = 0; d < dim; ++d)
          haptic << ',' << sample.force[d];
        haptic << ',' << sample.error << '\n';
      }
    haptic << std::flush;
    force << time << ',' << (record.engaged ? 1 : 0);
    for (unsigned int d = 0; d < dim; ++d)
      force << ',' << record.position[d];
    for (unsigned int d = 0; d < dim; ++d)
      force << ',' << record.force[d];
    force << '\n' << std::flush;
  }


  template <int dim>
  void
  ToolForce<dim>::finish(const time::State &,
                         const RunTotals &,
                         output::RunRecord &)
  {
    for (const auto &[name, tool] : this->context->scene.tools)
      parallel_tools::screen() << tool->summary() << std::endl;
  }

  template class ToolForce<1>;
  template class ToolForce<2>;
  template class ToolForce<3>;

  TISSUEFEM_REGISTER_POSTPROCESSOR(
    ToolForce,
    "tool force",
    "with tools: tool_force.csv (the force on the tool every step), "
    "haptic_force.csv (the forces sent to a haptic device between steps) "
    "and the haptic report; with several tools, one pair of files each, "
    "named tool_force-NAME.csv and haptic_force-NAME.csv.")
} // namespace tissuefem::postprocess
