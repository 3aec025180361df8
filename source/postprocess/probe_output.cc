#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/output/output_files.h>
#include <tissuefem/postprocess/probe_output.h>

#include <sstream>

#include <tissuefem/base/moved_entries.h>

namespace tissuefem::postprocess
{
  template <int dim>
  void
  ProbeOutput<dim>::declare_parameters(ParameterHandler &prm)
  {
    moved_entries::declare(
      prm,
      "Output/Probe points",
      "Output/Probes/Points",
      "",
      Patterns::Anything(),
      "Reference points 'x, y, z' separated by ';' at which the displacement "
      "goes to probes.csv every step (Dimension coordinates per point).");
  }


  template <int dim>
  ProbeOutput<dim>::ProbeOutput(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.enter_subsection("Probes");
    const std::string text = prm.get("Points");
    prm.leave_subsection();
    prm.leave_subsection();
    points = parse_points<dim>(text, "Output/Probes/Points");
  }


  template <int dim>
  void
  ProbeOutput<dim>::locate()
  {
    const auto &d = this->context->scene.solid->get_discretization();
    probes        = std::make_unique<output::Probes<dim>>(points,
                                                   *d.mapping,
                                                   d.dof_handler,
                                                   "Output/Probes/Points");
  }


  template <int dim>
  void
  ProbeOutput<dim>::initialize(const Context<dim> &c)
  {
    Interface<dim>::initialize(c);
    locate();
    follow_mesh
      = c.scene.solid->signals.changed.connect([this]() { locate(); });
  }


  template <int dim>
  std::vector<std::string>
  ProbeOutput<dim>::files() const
  {
    return {this->context->directory + "/probes.csv"};
  }


  template <int dim>
  void
  ProbeOutput<dim>::open()
  {
    if (!parallel_tools::is_root())
      return;
    static const char *coordinates[]   = {"X", "Y", "Z"};
    static const char *displacements[] = {"ux", "uy", "uz"};
    output::create_file(file, files()[0]);
    file << "time,probe";
    for (unsigned int d = 0; d < dim; ++d)
      file << ',' << coordinates[d];
    for (unsigned int d = 0; d < dim; ++d)
      file << ',' << displacements[d];
    file << '\n' << std::flush;
  }


  template <int dim>
  void
  ProbeOutput<dim>::restore(const std::vector<std::string> &)
  {
    if (parallel_tools::is_root())
      output::append_to_file(file, files()[0]);
  }


  template <int dim>
  void
  ProbeOutput<dim>::execute(const Step<dim> &step)
  {
    const auto values = probes->evaluate(step.u_ghosted);
    if (!parallel_tools::is_root())
      return;
    const double time      = step.state.time;
    const bool   summarize = this->context->summary.due(step.number);
    for (unsigned int p = 0; p < values.size(); ++p)
      {
        std::ostringstream row;
        row << std::setprecision(10) << time << ',' << p;
        for (unsigned int c = 0; c < dim; ++c)
          row << ',' << points[p][c];
        for (unsigned int c = 0; c < dim; ++c)
          row << ',' << values[p][c];
        file << row.str() << '\n';
        if (summarize)
          {
            auto          &summary = this->context->summary;
            Vector<double> scaled(values[p]);
            scaled /= summary.displacement_unit();
            summary.line(output::vector_line(time,
                                             "probe " + std::to_string(p) + " u"
                                               + summary.unit_label(),
                                             scaled,
                                             dim));
          }
      }
    file << std::flush;
  }

  template class ProbeOutput<1>;
  template class ProbeOutput<2>;
  template class ProbeOutput<3>;

  TISSUEFEM_REGISTER_POSTPROCESSOR(
    ProbeOutput,
    "probes",
    "probes.csv: the displacement at 'Output/Probes/Points' every step.")
} // namespace tissuefem::postprocess
