#include <deal.II/base/data_out_base.h>
#include <deal.II/numerics/data_component_interpretation.h>
#include <deal.II/numerics/data_out.h>

#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/output/checkpoint.h>
#include <tissuefem/output/output_files.h>
#include <tissuefem/postprocess/vtu_output.h>
#include <tissuefem/solid/quantities.h>

#include <iomanip>
#include <sstream>

#include <tissuefem/base/moved_entries.h>

namespace tissuefem::postprocess
{
  template <int dim>
  void
  VtuOutput<dim>::declare_parameters(ParameterHandler &prm)
  {
    moved_entries::declare(prm,
                           "Output/VTU interval",
                           "Output/VTU/Interval",
                           "1",
                           Patterns::Integer(0),
                           "Write the fields every this many steps (and at "
                           "t = 0); 0 writes no VTU files.");
  }


  template <int dim>
  VtuOutput<dim>::VtuOutput(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.enter_subsection("VTU");
    interval = prm.get_integer("Interval");
    prm.leave_subsection();
    prm.leave_subsection();
  }


  template <int dim>
  std::vector<std::string>
  VtuOutput<dim>::save() const
  {
    // One line per record: time, then the file name (which may not hold
    // a line break, and holds no space).
    std::vector<std::string> lines;
    for (const auto &[time, name] : records)
      lines.push_back(output::exact_text(time) + ' ' + name);
    return lines;
  }


  template <int dim>
  void
  VtuOutput<dim>::restore(const std::vector<std::string> &lines)
  {
    records.clear();
    for (const std::string &line : lines)
      {
        const auto space = line.find(' ');
        records.emplace_back(output::exact_value(line.substr(0, space)),
                             line.substr(space + 1));
      }
  }


  template <int dim>
  void
  VtuOutput<dim>::execute(const Step<dim> &step)
  {
    if (interval == 0 || step.number % interval != 0)
      return;
    // DataOut reads ghost entries of the cells it writes.
    VectorType v;
    this->context->scene.solid->get_discretization().initialize_vector(v, true);
    v = step.state.v;
    write(step.number, step.state.time, step.u_ghosted, v);
  }


  template <int dim>
  void
  VtuOutput<dim>::write(const unsigned int step,
                        const double       time,
                        const VectorType  &u,
                        const VectorType  &v)
  {
    const auto &solid = *this->context->scene.solid;
    const auto &d     = solid.get_discretization();
    const std::vector<DataComponentInterpretation::DataComponentInterpretation>
      vector_field(dim,
                   DataComponentInterpretation::component_is_part_of_vector);

    Vector<float> jacobian, von_mises;
    solid::cell_fields(d,
                       solid.get_materials(),
                       solid.fibres(),
                       solid.deformation(u).get(),
                       u,
                       jacobian,
                       von_mises);
    const bool finite
      = Utilities::MPI::min((all_finite(jacobian) && all_finite(von_mises)) ? 1
                                                                            : 0,
                            parallel_tools::communicator());
    if (!finite)
      throw SolverError("non-finite J or stress at step " + std::to_string(step)
                        + "; VTU file not written");
    const auto   &triangulation = d.dof_handler.get_triangulation();
    Vector<float> material_id(triangulation.n_active_cells());
    Vector<float> process(triangulation.n_active_cells());
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        material_id[cell->active_cell_index()] = cell->material_id();
        process[cell->active_cell_index()]     = cell->subdomain_id();
      }

    DataOut<dim> data_out;
    data_out.attach_dof_handler(d.dof_handler);
    data_out.add_data_vector(u,
                             std::vector<std::string>(dim, "displacement"),
                             DataOut<dim>::type_dof_data,
                             vector_field);
    data_out.add_data_vector(v,
                             std::vector<std::string>(dim, "velocity"),
                             DataOut<dim>::type_dof_data,
                             vector_field);
    data_out.add_data_vector(jacobian, "J");
    data_out.add_data_vector(von_mises, "von_Mises_Cauchy_stress");
    data_out.add_data_vector(material_id, "material_id");
    data_out.add_data_vector(process, "process");
    const std::vector<Vector<float>> fibre
      = solid.fibres().cell_averages(triangulation.n_active_cells());
    static const char *fibre_names[] = {"fibre_x", "fibre_y", "fibre_z"};
    for (unsigned int c = 0; c < fibre.size(); ++c)
      data_out.add_data_vector(fibre[c], fibre_names[c]);
    Vector<float> contact_pressure, contact_gap;
    if (const auto &contact = this->context->scene.obstacle_contact)
      {
        contact->cell_fields(u, time, contact_pressure, contact_gap);
        data_out.add_data_vector(contact_pressure, "contact_pressure");
        data_out.add_data_vector(contact_gap, "contact_gap");
      }
    data_out.build_patches(*d.mapping, d.fe->degree);

    // One piece per process, a .pvtu naming them, and the .pvd series.
    std::ostringstream base;
    base << "solution-" << std::setw(5) << std::setfill('0') << step;
    const unsigned int rank
      = Utilities::MPI::this_mpi_process(parallel_tools::communicator());
    const std::string  piece = base.str() + "." + std::to_string(rank) + ".vtu";
    const std::string &directory = this->context->directory;
    output::write_whole(directory + "/" + piece,
                        [&](std::ostream &out) { data_out.write_vtu(out); });
    if (!parallel_tools::is_root())
      return;
    std::vector<std::string> pieces;
    for (unsigned int p = 0; p < parallel_tools::n_processes(); ++p)
      pieces.push_back(base.str() + "." + std::to_string(p) + ".vtu");
    const std::string master = base.str() + ".pvtu";
    output::write_whole(directory + "/" + master, [&](std::ostream &out) {
      data_out.write_pvtu_record(out, pieces);
    });
    records.emplace_back(time, master);
    output::write_whole(directory + "/solution.pvd", [&](std::ostream &out) {
      DataOutBase::write_pvd_record(out, records);
    });
  }

  template class VtuOutput<1>;
  template class VtuOutput<2>;
  template class VtuOutput<3>;

  TISSUEFEM_REGISTER_POSTPROCESSOR(
    VtuOutput,
    "VTU",
    "solution-NNNNN.pvtu/.vtu and solution.pvd: the fields for ParaView "
    "every 'Output/VTU/Interval' steps.")
} // namespace tissuefem::postprocess
