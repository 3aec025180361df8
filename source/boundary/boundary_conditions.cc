#include <deal.II/base/utilities.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/boundary/boundary_conditions.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <sstream>

namespace tissuefem::boundary
{
  void
  BoundaryParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary conditions");
    {
      prm.declare_entry(
        "Dirichlet",
        "",
        Patterns::Anything(),
        "Prescribed displacement: entries 'id: components: u_x; u_y; u_z' "
        "separated by '|'. 'components' is a subset of 'xyz' (which "
        "displacement components are prescribed); the expressions (one per "
        "dimension, or one for all) are functions of x, y, z, t in length "
        "units. Example: '0: xy: 0; 0 | 1: y: -0.1*t'.");
      prm.declare_entry(
        "Neumann",
        "",
        Patterns::Anything(),
        "Prescribed traction P N per unit reference area (Pa if SI): entries "
        "'id: h_x; h_y; h_z' separated by '|'. Boundaries listed nowhere are "
        "traction free.");
      prm.declare_entry("Body force",
                        "0",
                        Patterns::Anything(),
                        "Force per unit reference volume (N/m^3 if SI), "
                        "'f_x; f_y; f_z' as functions of x, y, z, t.");
      prm.declare_entry("Gravity",
                        "0, 0, 0",
                        Patterns::Anything(),
                        "Acceleration of gravity 'g_x, g_y, g_z' (m/s^2 if "
                        "SI); contributes rho_0 g per unit reference volume. "
                        "Only the first Dimension components are read.");
      prm.declare_entry(
        "Load factor",
        "automatic",
        Patterns::Anything(),
        "lambda(t), a dimensionless function of t that multiplies every "
        "load: gravity, body force and tractions. Prescribed displacements "
        "are not scaled: their expressions name t themselves. 'automatic' "
        "(the default) is t / End time in a quasistatic run, so that the "
        "loads grow from zero to their full size at the end of the run, as "
        "Abaqus's static steps and FEBio's load curves do (each step then "
        "starts near the last equilibrium), and 1 in a dynamic run or with "
        "a manufactured solution; the run's first lines say which factor "
        "is in force. '1' applies the loads as given at every time; "
        "'min(t, 1)' ramps them up over the first time unit. Whatever the "
        "factor, a quasistatic step that Newton cannot take is retried "
        "from the last equilibrium with half its load increment (load "
        "continuation, down to 'Time integration/Maximum step halvings'), "
        "and a run that stops reports the load factor it reached. A "
        "manufactured solution needs 1 (or automatic).");
      prm.declare_entry("Initial displacement",
                        "0",
                        Patterns::Anything(),
                        "u at t = 0, 'u_x; u_y; u_z' as functions of x, y, z.");
      prm.declare_entry("Initial velocity",
                        "0",
                        Patterns::Anything(),
                        "v at t = 0, 'v_x; v_y; v_z' as functions of x, y, z.");
    }
    prm.leave_subsection();
  }


  void
  BoundaryParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary conditions");
    dirichlet            = prm.get("Dirichlet");
    neumann              = prm.get("Neumann");
    body_force           = prm.get("Body force");
    gravity              = prm.get("Gravity");
    initial_displacement = prm.get("Initial displacement");
    initial_velocity     = prm.get("Initial velocity");
    load_factor          = prm.get("Load factor");
    prm.leave_subsection();
  }


  namespace
  {
    template <int dim>
    ComponentMask
    parse_mask(const std::string &text, const std::string &parameter)
    {
      const std::string names = std::string("xyz").substr(0, dim);
      std::vector<bool> mask(dim, false);
      for (const char c : text)
        {
          const auto d = names.find(c);
          require(d != std::string::npos,
                  parameter,
                  "components '" + text + "' must be letters of '" + names
                    + "'");
          mask[d] = true;
        }
      require(!text.empty(), parameter, "empty component list");
      return ComponentMask(mask);
    }

    /// Whether an expression uses the time t; constants and functions of
    /// x, y, z alone do not.
    bool
    names_time(const std::string &expression)
    {
      return names_variable(expression, "t");
    }
  } // namespace


  void
  BoundaryParameters::resolve_load_factor(const bool         quasistatic,
                                          const std::string &end_time)
  {
    if (Utilities::trim(load_factor) != "automatic")
      return;
    // Loads whose own expressions name t are ramped already: a factor
    // t / T on top would make their ramp quadratic.
    if (quasistatic && !names_time(neumann) && !names_time(body_force))
      {
        load_factor      = "t / (" + Utilities::trim(end_time) + ")";
        load_factor_note = "automatic: a quasistatic run ramps its loads";
      }
    else
      {
        load_factor      = "1";
        load_factor_note = quasistatic ? "automatic: the loads' own "
                                         "expressions name t"
                                       : "automatic: a dynamic run";
      }
  }


  template <int dim>
  BoundaryConditions<dim>::BoundaryConditions(
    const BoundaryParameters &parameters)
  {
    // Entries are split at their first colons only, so that expressions
    // may use muparser's ternary operator 'a ? b : c'.
    const std::string dirichlet_name = "Boundary conditions/Dirichlet";
    for (const auto &[id, rest] :
         parse_id_entries(parameters.dirichlet, dirichlet_name))
      {
        const auto colon = rest.find(':');
        require(colon != std::string::npos,
                dirichlet_name,
                "entry '" + rest + "' for boundary " + std::to_string(id)
                  + " is not 'components: expressions'");
        dirichlet.push_back(
          {id,
           parse_mask<dim>(Utilities::trim(rest.substr(0, colon)),
                           dirichlet_name),
           make_function<dim>(rest.substr(colon + 1), dim, dirichlet_name),
           names_time(rest.substr(colon + 1))});
      }

    const std::string neumann_name = "Boundary conditions/Neumann";
    for (const auto &[id, expressions] :
         parse_id_entries(parameters.neumann, neumann_name))
      {
        neumann.push_back(
          {id, make_function<dim>(expressions, dim, neumann_name)});
        loads_name_time_ = loads_name_time_ || names_time(expressions);
      }
    factor_expression = Utilities::trim(parameters.load_factor);
    factor_note       = parameters.load_factor_note;
    require(factor_expression != "automatic",
            "Boundary conditions/Load factor",
            "'automatic' must be resolved by the scene "
            "(BoundaryParameters::resolve_load_factor)");
    factor_names_time = names_time(parameters.load_factor);
    loads_name_time_  = loads_name_time_ || names_time(parameters.body_force)
                       || factor_names_time;
    const std::string load_factor_name = "Boundary conditions/Load factor";
    for (const char *space : {"x", "y", "z"})
      require(!names_variable(parameters.load_factor, space),
              load_factor_name,
              "must be a function of t only; '" + parameters.load_factor
                + "' names " + space);
    load_factor_function
      = make_function<dim>(parameters.load_factor, 1, load_factor_name);
    load_factor = load_factor_at(0);
    require(std::isfinite(load_factor),
            load_factor_name,
            "is not finite at t = 0");

    body_force         = make_function<dim>(parameters.body_force,
                                    dim,
                                    "Boundary conditions/Body force");
    body_force_is_zero = true;
    for (const auto &expression : split_and_trim(parameters.body_force, ';'))
      body_force_is_zero = body_force_is_zero && expression == "0";
    gravity = parse_leading_point<dim>(parameters.gravity,
                                       "Boundary conditions/Gravity");

    initial_displacement
      = make_function<dim>(parameters.initial_displacement,
                           dim,
                           "Boundary conditions/Initial displacement");
    initial_velocity
      = make_function<dim>(parameters.initial_velocity,
                           dim,
                           "Boundary conditions/Initial velocity");
  }


  template <int dim>
  void
  BoundaryConditions<dim>::set_time(const double time)
  {
    for (auto &d : dirichlet)
      d.displacement->set_time(time);
    for (auto &n : neumann)
      n.traction->set_time(time);
    body_force->set_time(time);
    load_factor = load_factor_in_force(time);
  }


  template <int dim>
  double
  BoundaryConditions<dim>::load_factor_in_force(const double time) const
  {
    return held_load_factor ? *held_load_factor : load_factor_at(time);
  }


  template <int dim>
  double
  BoundaryConditions<dim>::load_factor_at(const double time) const
  {
    load_factor_function->set_time(time);
    return load_factor_function->value(Point<dim>());
  }


  template <int dim>
  std::string
  BoundaryConditions<dim>::describe_load_factor() const
  {
    std::string text = "load factor lambda(t) = " + factor_expression
                       + " (scales gravity, body force and tractions";
    if (!factor_note.empty())
      text += "; " + factor_note;
    return text + ")";
  }


  template <int dim>
  bool
  BoundaryConditions<dim>::load_factor_names_time() const
  {
    return factor_names_time;
  }


  template <int dim>
  bool
  BoundaryConditions<dim>::changes_with_time() const
  {
    // A factor that names t changes nothing where there is no load (the
    // automatic ramp of a quasistatic run driven by displacements).
    return (loads_name_time_ && has_loads())
           || std::any_of(dirichlet.begin(),
                          dirichlet.end(),
                          [](const Dirichlet &d) { return d.time_dependent; });
  }


  template <int dim>
  bool
  BoundaryConditions<dim>::has_loads() const
  {
    return gravity.norm() > 0 || !body_force_is_zero || !neumann.empty();
  }


  template <int dim>
  void
  BoundaryConditions<dim>::check_boundary_ids(
    const Triangulation<dim> &triangulation) const
  {
    const std::vector<types::boundary_id> present
      = triangulation.get_boundary_ids();
    const std::set<types::boundary_id> ids(present.begin(), present.end());
    for (const auto &d : dirichlet)
      require(ids.count(d.id) > 0,
              "Boundary conditions/Dirichlet",
              "boundary id " + std::to_string(d.id)
                + " is on no boundary face of the mesh");
    for (const auto &n : neumann)
      require(ids.count(n.id) > 0,
              "Boundary conditions/Neumann",
              "boundary id " + std::to_string(n.id)
                + " is on no boundary face of the mesh");
  }

  template class BoundaryConditions<1>;
  template class BoundaryConditions<2>;
  template class BoundaryConditions<3>;
} // namespace tissuefem::boundary
