#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/contact/obstacle.h>

#include <filesystem>

namespace tissuefem::contact
{
  template <int dim>
  void
  Obstacle<dim>::declare_parameters(ParameterHandler &prm)
  {
    const auto &shapes = ShapeRegistry<dim>::instance();
    prm.enter_subsection("Contact");
    for (unsigned int k = 1; k <= max_obstacles; ++k)
      {
        prm.enter_subsection("Obstacle " + std::to_string(k));
        prm.declare_entry("Shape",
                          "none",
                          Patterns::Selection("none|"
                                              + shapes.selection_pattern()),
                          "The rigid shape of this obstacle, or 'none' for "
                          "no obstacle. "
                            + shapes.documentation()
                            + "Its parameters are in the subsection of the "
                              "shape's name.");
        prm.declare_entry("Name",
                          "obstacle " + std::to_string(k),
                          Patterns::Anything(),
                          "The obstacle's name in contact.csv and the "
                          "summary file.");
        prm.declare_entry(
          "Motion",
          "0",
          Patterns::Anything(),
          "Translation of the shape from where its "
          "parameters put it (length units): expressions of "
          "t (time units), one per coordinate separated by "
          "';' (the first dim are used), or one for all. The shape moves "
          "rigidly: "
          "contact pushes the tissue, never the obstacle.");
        prm.declare_entry(
          "Motion file",
          "",
          Patterns::Anything(),
          "A CSV file of the shape's translation against time, recorded "
          "from a device or written by hand: rows 't, x, y[, z]' (time and "
          "length units), times increasing, a first line that is not "
          "numeric a header; interpolated linearly and held beyond the "
          "ends. A relative path is taken relative to the parameter file's "
          "directory. Replaces 'Motion' when set.");
        prm.declare_entry(
          "Friction coefficient",
          "0",
          Patterns::Double(0),
          "Coulomb's coefficient mu between this obstacle and the tissue "
          "(dimensionless, >= 0; 0 is frictionless): a contact point "
          "sticks while its tangential traction is below mu times its "
          "contact pressure and slides against it otherwise. Any "
          "'Contact/Method'; implicit steps solve again until the bound "
          "settles, explicit steps take the bound of the step before.");
        shapes.declare_parameters(prm);
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }


  template <int dim>
  std::vector<Obstacle<dim>>
  Obstacle<dim>::create_all(ParameterHandler &prm, const std::string &directory)
  {
    std::vector<Obstacle<dim>> result;
    prm.enter_subsection("Contact");
    for (unsigned int k = 1; k <= max_obstacles; ++k)
      {
        const std::string slot = "Obstacle " + std::to_string(k);
        prm.enter_subsection(slot);
        const std::string shape = prm.get("Shape");
        if (shape != "none")
          {
            Obstacle<dim> obstacle;
            obstacle.slot = "Contact/" + slot;
            obstacle.name = Utilities::trim(prm.get("Name"));
            require(!obstacle.name.empty()
                      && obstacle.name.find_first_of(",\n")
                           == std::string::npos,
                    "Contact/" + slot + "/Name",
                    "must be a non-empty name without commas");
            for (const auto &other : result)
              require(other.name != obstacle.name,
                      "Contact/" + slot + "/Name",
                      "'" + obstacle.name + "' names two obstacles");
            obstacle.moves = names_variable(prm.get("Motion"), "t");
            obstacle.own_motion_names_t = obstacle.moves;
            if (std::string file = Utilities::trim(prm.get("Motion file"));
                !file.empty())
              {
                if (std::filesystem::path(file).is_relative()
                    && !directory.empty())
                  file = (std::filesystem::path(directory) / file).string();
                obstacle.recorded = std::make_shared<TrajectoryTable<dim>>(
                  TrajectoryTable<dim>::read(file,
                                             "Contact/" + slot
                                               + "/Motion file"));
                obstacle.moves = true;
              }
            obstacle.friction = prm.get_double("Friction coefficient");
            obstacle.motion
              = make_function<dim>(leading_entries(prm.get("Motion"), ';', dim),
                                   dim,
                                   "Contact/" + slot + "/Motion");
            try
              {
                obstacle.shape
                  = ShapeRegistry<dim>::instance().create(shape,
                                                          prm,
                                                          directory);
              }
            catch (const InputError &e)
              {
                throw InputError(std::string(e.what()) + " (in Contact/" + slot
                                 + ")");
              }
            result.push_back(std::move(obstacle));
          }
        prm.leave_subsection();
      }
    prm.leave_subsection();
    return result;
  }


  template <int dim>
  Tensor<1, dim>
  Obstacle<dim>::offset(const double time) const
  {
    if (follower)
      return follower(time);
    if (recorded)
      return recorded->position(time);
    motion->set_time(time);
    Tensor<1, dim> result;
    for (unsigned int d = 0; d < dim; ++d)
      result[d] = motion->value(Point<dim>(), d);
    return result;
  }


  template class Obstacle<1>;
  template class Obstacle<2>;
  template class Obstacle<3>;
} // namespace tissuefem::contact
