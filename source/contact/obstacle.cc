#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/contact/obstacle.h>

#include <algorithm>
#include <filesystem>

namespace tissuefem::contact
{
  template <int dim>
  void
  Obstacle<dim>::declare_parameters(ParameterHandler &prm)
  {
    const auto &shapes = ShapeRegistry<dim>::instance();
    prm.enter_subsection("Contact");
    for (unsigned int k = 1; k <= obstacle_slots(); ++k)
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
          "Rotation",
          "0",
          Patterns::Anything(),
          "Rotation of the shape about 'Rotation centre' (radians), "
          "expressions of t (time units): in 2D exactly one, the angle, "
          "counter-clockwise; in 3D exactly three separated by ';', the "
          "rotation vector (the axis times the angle, turning right-handed "
          "about the axis); 0 for none; ignored in 1D. A point y of the shape "
          "(where "
          "its parameters put it) goes to c + m + R (y - c), c the centre, "
          "R the rotation and m 'Motion': a pivoting instrument, a tilting "
          "table. Friction's stick points turn with the shape. A live "
          "device moves the translation; the rotation stays this one.");
        prm.declare_entry("Rotation centre",
                          "0, 0, 0",
                          Patterns::Anything(),
                          "The point of the shape's frame about which "
                          "'Rotation' turns it (length units; the first dim "
                          "coordinates are used): a trocar's pivot, a "
                          "hinge.");
        prm.declare_entry(
          "Motion file",
          "",
          Patterns::Anything(),
          "A CSV file of the shape's poses against time, recorded from a "
          "device or written by hand: rows 't, x, y[, z]' (time and length "
          "units, the translation) or, with the rotation (radians, as "
          "'Rotation' gives it, unwrapped: interpolated linearly, an angle "
          "that jumps from pi to -pi turns the long way), 't, x, y, angle' "
          "in 2D (so a fourth column is an angle there) and 't, x, y, z, "
          "rx, ry, rz' in 3D, every row as wide as the first; times "
          "increasing, a first line that is not numeric a header; "
          "interpolated linearly and held beyond the ends. A relative path "
          "is taken relative to the parameter file's directory. Replaces "
          "'Motion' when set, and 'Rotation' when its rows carry one.");
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
    // The slots @p prm declared (obstacle_slots() may have been raised
    // since, for another file).
    for (unsigned int k = 1;
         prm.subsection_path_exists({"Obstacle " + std::to_string(k)});
         ++k)
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
            obstacle.own_motion_names_t
              = names_variable(prm.get("Motion"), "t");
            obstacle.moves = obstacle.own_motion_names_t;
            obstacle.read_rotation(prm, slot);
            if (std::string file = Utilities::trim(prm.get("Motion file"));
                !file.empty())
              {
                if (std::filesystem::path(file).is_relative()
                    && !directory.empty())
                  file = (std::filesystem::path(directory) / file).string();
                obstacle.recorded = std::make_shared<TrajectoryTable<dim>>(
                  TrajectoryTable<dim>::read(file,
                                             "Contact/" + slot + "/Motion file",
                                             rotation_components(dim)));
                obstacle.moves = true;
                if (obstacle.recorded->has_rotation())
                  obstacle.rotating = true;
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
  void
  Obstacle<dim>::read_rotation(ParameterHandler &prm, const std::string &slot)
  {
    const std::string where = "Contact/" + slot + "/";
    pivot
      = parse_point<dim>(leading_entries(prm.get("Rotation centre"), ',', dim),
                         where + "Rotation centre");
    constexpr unsigned int n = rotation_components(dim);
    if (n == 0)
      return;
    // Exactly the rotation's own components: one expression copied to
    // three would turn about (1, 1, 1), and the first of three kept in 2D
    // would not be the angle about the plane's normal.
    const std::string text    = Utilities::trim(prm.get("Rotation"));
    const auto        entries = Utilities::split_string_list(text, ';');
    require(entries.size() == n || text == "0",
            where + "Rotation",
            n == 1 ? "needs one expression, the angle (radians), in 2D; got "
                       + std::to_string(entries.size())
                   : "needs three expressions separated by ';', the rotation "
                     "vector (radians), in 3D; got "
                       + std::to_string(entries.size()));
    rotation = make_function<dim>(text, n, where + "Rotation");
    moves    = moves || names_variable(text, "t");
    rotating = names_variable(text, "t");
    rotation->set_time(0);
    for (unsigned int r = 0; r < n; ++r)
      rotating = rotating || rotation->value(Point<dim>(), r) != 0;
  }


  template <int dim>
  Pose<dim>
  Obstacle<dim>::pose(const double time) const
  {
    Pose<dim> result;
    result.pivot = pivot;
    if (follower)
      result.translation = follower(time);
    else if (recorded)
      result.translation = recorded->position(time);
    else
      {
        motion->set_time(time);
        for (unsigned int d = 0; d < dim; ++d)
          result.translation[d] = motion->value(Point<dim>(), d);
      }
    if (!rotating)
      return result;
    std::array<double, 3> angles{{0, 0, 0}};
    if (recorded && recorded->has_rotation())
      angles = recorded->rotation(time);
    else
      {
        rotation->set_time(time);
        for (unsigned int r = 0; r < rotation_components(dim); ++r)
          angles[r] = rotation->value(Point<dim>(), r);
      }
    result.rotation = rotation_matrix<dim>(angles);
    result.rotates  = angles[0] != 0 || angles[1] != 0 || angles[2] != 0;
    return result;
  }


  namespace
  {
    unsigned int &
    slots()
    {
      static unsigned int count = max_obstacles;
      return count;
    }
  } // namespace


  unsigned int
  obstacle_slots()
  {
    return slots();
  }


  void
  name_obstacle_slot(const std::string &k, const std::string &where)
  {
    const unsigned long slot
      = k.size() > 6 ? largest_obstacle_slot + 1 : std::stoul(k);
    if (slot == 0 || slot > largest_obstacle_slot)
      throw InputError(where + ": 'Obstacle " + k
                       + "': obstacle slots go from 1 to "
                       + std::to_string(largest_obstacle_slot));
    slots() = std::max<unsigned int>(slots(), slot);
  }


  template class Obstacle<1>;
  template class Obstacle<2>;
  template class Obstacle<3>;
} // namespace tissuefem::contact
