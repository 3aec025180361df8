#include <deal.II/base/utilities.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/tool/contact_tool.h>

#include <iomanip>
#include <sstream>

namespace tissuefem::tool
{
  template <int dim>
  void
  ContactTool<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Contact tool");
    prm.declare_entry("Obstacle",
                      "",
                      Patterns::Anything(),
                      "The 'Name' of the obstacle (a 'Contact/Obstacle k') "
                      "that is the instrument in the user's hand: the force "
                      "of the tissue on it goes to tool_force.csv and to a "
                      "haptic device; with a 'Live port' it follows the "
                      "live client (its own 'Motion' must then be 0). Empty: "
                      "no contact tool.");
    HapticParameters::declare_parameters(prm);
    prm.leave_subsection();
  }


  template <int dim>
  std::unique_ptr<Interface<dim>>
  ContactTool<dim>::create(ParameterHandler &prm, const Triangulation<dim> &)
  {
    prm.enter_subsection("Contact tool");
    const std::string obstacle = Utilities::trim(prm.get("Obstacle"));
    HapticParameters  haptic;
    haptic.parse_parameters(prm, "Contact tool", !obstacle.empty());
    prm.leave_subsection();
    if (obstacle.empty())
      return nullptr;
    // A live device moves the tool by itself; otherwise a page may.
    prm.enter_subsection("Output");
    prm.enter_subsection("Live view");
    const bool view = prm.get_integer("Port") >= 0;
    prm.leave_subsection();
    prm.leave_subsection();
    return std::make_unique<ContactTool<dim>>(
      obstacle, haptic, view && dim >= 2 && haptic.live_port < 0);
  }


  template <int dim>
  ContactTool<dim>::ContactTool(const std::string      &obstacle,
                                const HapticParameters &parameters,
                                const bool              mouse)
      : obstacle_name(obstacle)
      , haptic(parameters, [this](const double t) { return displacement(t); })
      , mouse(mouse)
  {
  }


  template <int dim>
  void
  ContactTool<dim>::attach(contact::PenaltyContact<dim> *c)
  {
    require(c != nullptr,
            "Contact tool/Obstacle",
            "names '" + obstacle_name
              + "', but the scene has no obstacle ('Contact/Obstacle k/"
                "Shape' is 'none' in every slot)");
    auto       &obstacles = c->obstacles();
    std::string names;
    for (index = 0; index < obstacles.size(); ++index)
      if (obstacles[index].name == obstacle_name)
        break;
      else
        names += (names.empty() ? "'" : ", '") + obstacles[index].name + "'";
    require(index < obstacles.size(),
            "Contact tool/Obstacle",
            "names '" + obstacle_name + "', which is no obstacle of the scene "
              + "(they are " + names + ")");
    contact = c;
    if (haptic.live())
      {
        require(!obstacles[index].has_own_motion(),
                obstacles[index].slot + "/Motion",
                "must be 0 without a 'Motion file': the obstacle follows the "
                "live client of 'Contact tool/Live port'");
        // A live tool is where its parameters put it until the first
        // position arrives, then moves by the positions minus the first.
        const TrajectoryTable<dim> *positions = &table;
        obstacles[index].follow([positions](const double t) {
          return positions->position(t) - positions->first();
        });
      }
    else if (mouse)
      {
        // Its own motion, and the mouse's offset on top; displacements
        // count from where its own motion starts.
        const contact::Obstacle<dim> own = obstacles[index];
        start                            = own.pose(0.).translation;
        obstacles[index].follow([own, offset = motion](const double t) {
          return own.pose(t).translation + (*offset)(t);
        });
      }
  }


  template <int dim>
  std::string
  ContactTool<dim>::request_move(const Tensor<1, dim> &offset)
  {
    if (!mouse)
      return "the contact tool follows its live device";
    if (std::string why = motion->refusal(offset, "tool offset"); !why.empty())
      return why;
    asked_offset = offset;
    return {};
  }


  template <int dim>
  Tensor<1, dim>
  ContactTool<dim>::displacement(const double time) const
  {
    const auto &obstacle = contact->obstacles()[index];
    return obstacle.pose(time).translation
           - (mouse ? start : obstacle.pose(0.).translation);
  }


  template <int dim>
  void
  ContactTool<dim>::connect(const std::string &directory,
                            const double       body_diameter)
  {
    haptic.connect(directory, body_diameter);
    motion->scale(body_diameter);
  }


  template <int dim>
  bool
  ContactTool<dim>::synchronize(const double time)
  {
    if (mouse)
      {
        const Tensor<1, dim> target
          = Utilities::MPI::broadcast(parallel_tools::communicator(),
                                      asked_offset);
        motion->advance(time, target);
      }
    return haptic.synchronize(time, table);
  }


  template <int dim>
  std::string
  ContactTool<dim>::live_end() const
  {
    return haptic.live_end();
  }


  template <int dim>
  Record<dim>
  ContactTool<dim>::record(const time::State &state,
                           solid::Solid<dim> &,
                           const contact::Reports<dim> &reports)
  {
    AssertDimension(reports.size(), contact->obstacles().size());
    Record<dim> result;
    result.position = displacement(state.time);
    result.force    = -reports[index].force;
    result.engaged  = reports[index].area > 0;
    result.haptic   = haptic.update(state.time, result.force, result.engaged);
    ++steps;
    if (result.engaged)
      ++steps_touching;
    return result;
  }


  template <int dim>
  std::string
  ContactTool<dim>::summary() const
  {
    std::ostringstream s;
    s << "contact tool '" << obstacle_name << "': touched the tissue at "
      << steps_touching << " of " << steps << " states; " << haptic.summary();
    return s.str();
  }

  template class ContactTool<1>;
  template class ContactTool<2>;
  template class ContactTool<3>;

  TISSUEFEM_REGISTER_TOOL(ContactTool,
                          "contact",
                          "the obstacle named by 'Contact tool/Obstacle' as an "
                          "instrument: its force to tool_force.csv and a "
                          "haptic device, its motion from a live client.")
} // namespace tissuefem::tool
