#include <tissuefem/output/output_files.h>
#include <tissuefem/postprocess/contact_output.h>

namespace tissuefem::postprocess
{
  template <int dim>
  void
  ContactOutput<dim>::declare_parameters(ParameterHandler &)
  {
    // Written whenever the scene has obstacles: nothing to choose.
  }


  template <int dim>
  ContactOutput<dim>::ContactOutput(ParameterHandler &)
  {
  }


  template <int dim>
  std::vector<std::string>
  ContactOutput<dim>::files() const
  {
    if (!this->context->scene.obstacle_contact)
      return {};
    return {this->context->directory + "/contact.csv"};
  }


  template <int dim>
  void
  ContactOutput<dim>::open()
  {
    if (!this->context->scene.obstacle_contact || !parallel_tools::is_root())
      return;
    static const char *coordinates[] = {"X", "Y", "Z"};
    output::create_file(file, files()[0]);
    file << "time,obstacle";
    for (unsigned int d = 0; d < dim; ++d)
      file << ",F" << coordinates[d];
    file << ",penetration,area,min pressure,max pressure\n" << std::flush;
  }


  template <int dim>
  void
  ContactOutput<dim>::restore(const std::vector<std::string> &)
  {
    if (this->context->scene.obstacle_contact && parallel_tools::is_root())
      output::append_to_file(file, files()[0]);
  }


  template <int dim>
  void
  ContactOutput<dim>::execute(const Step<dim> &step)
  {
    if (!this->context->scene.obstacle_contact || !parallel_tools::is_root())
      return;
    const auto &reports   = step.contact;
    const bool  summarize = this->context->summary.due(step.number);
    for (const auto &r : reports)
      {
        file << step.state.time << ',' << r.name;
        for (unsigned int d = 0; d < dim; ++d)
          file << ',' << r.force[d];
        file << ',' << r.penetration << ',' << r.area << ',' << r.min_pressure
             << ',' << r.max_pressure << '\n';
        if (summarize)
          {
            this->context->summary.line(output::vector_line(
              step.state.time, "obstacle " + r.name + " force", r.force, dim));
            this->context->summary.line(
              output::vector_line(step.state.time,
                                  "obstacle " + r.name + " penetration",
                                  &r.penetration,
                                  1));
            const double range[] = {r.min_pressure, r.max_pressure};
            this->context->summary.line(
              output::vector_line(step.state.time,
                                  "obstacle " + r.name + " pressure range",
                                  range,
                                  2));
          }
      }
    file << std::flush;
  }

  template class ContactOutput<1>;
  template class ContactOutput<2>;
  template class ContactOutput<3>;

  TISSUEFEM_REGISTER_POSTPROCESSOR(
    ContactOutput,
    "contact",
    "contact.csv: per obstacle and step, its force on the tissue (force "
    "units), the largest penetration (length units), the area carrying a "
    "pressure (length^(dim-1)) and the smallest and largest contact "
    "pressure there (stress units).")
} // namespace tissuefem::postprocess
