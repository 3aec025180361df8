#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/contact/penalty_contact.h>
#include <tissuefem/contact/self_contact.h>
#include <tissuefem/geometry/mesh_parts.h>
#include <tissuefem/scene/scene.h>
#include <tissuefem/time/interface.h>

#include <sstream>

namespace tissuefem
{
  namespace
  {
    using Capabilities = time::Interface::Capabilities;

    /// The integrator 'Time integration/Integrator' names, and what it can
    /// take with the settings of @p prm (asked once: building an
    /// integrator reads its parameters).
    struct ChosenIntegrator
    {
      explicit ChosenIntegrator(ParameterHandler &prm)
      {
        parameters.parse_parameters(prm);
        can = time::IntegratorRegistry::instance()
                .create(parameters.integrator, prm)
                ->capabilities();
      }

      time::TimeParameters parameters;
      Capabilities         can;
    };

    /// The registered integrators that, with their default settings, have
    /// the capability @p has: "a, b or c", for messages.
    std::string
    integrators_with(bool Capabilities::*has)
    {
      ParameterHandler defaults;
      time::TimeParameters::declare_parameters(defaults);
      std::vector<std::string> names;
      for (const auto &[name, entry] :
           time::IntegratorRegistry::instance().all())
        if (entry.create(defaults)->capabilities().*has)
          names.push_back(name);
      std::string list;
      for (unsigned int i = 0; i < names.size(); ++i)
        list += (i == 0                  ? ""
                 : i + 1 == names.size() ? " or "
                                         : ", ")
                + names[i];
      return list;
    }
  } // namespace


  template <int dim>
  void
  Scene<dim>::declare_parameters(ParameterHandler &prm)
  {
    tool::ToolRegistry<dim>::instance().declare_parameters(prm);
    boundary::ManufacturedParameters::declare_parameters(prm);
    contact::Obstacle<dim>::declare_parameters(prm);
    contact::PenaltyContact<dim>::declare_parameters(prm);
  }


  namespace
  {
    /**
     * Rayleigh damping needs an integrator that applies it; self contact
     * one that begins each step (where it takes its weights); contact with
     * obstacles one that takes a penalty force of (u, t) (the penalty
     * method, obstacles that may move) or one that updates contact
     * multipliers (the augmented Lagrangian). Others would ignore them
     * unseen.
     */
    template <int dim>
    void
    check_integrator_capabilities(
      ParameterHandler                          &prm,
      const ChosenIntegrator                    &integrator,
      const double                               self_contact_pressure,
      const std::vector<contact::Obstacle<dim>> &obstacles)
    {
      const Capabilities &can = integrator.can;
      // The lists of integrators are made only for a message (each
      // constructs every registered integrator).
      const auto refuse = [&](const std::string &parameter,
                              const std::string &what,
                              bool Capabilities::*needed,
                              const std::string  &why = "") {
        throw InputError("Parameter '" + parameter + "': " + what
                         + " Time integration/Integrator = "
                         + integrators_with(needed) + " (not '"
                         + integrator.parameters.integrator + "'"
                         + (why.empty() ? "" : ": " + why) + ")");
      };
      for (const auto &[name, value] :
           {std::pair("mass", integrator.parameters.rayleigh_mass),
            std::pair("stiffness", integrator.parameters.rayleigh_stiffness)})
        if (value != 0 && !can.rayleigh_damping)
          refuse(std::string("Time integration/Rayleigh ") + name + " damping",
                 "must be 0 unless",
                 &Capabilities::rayleigh_damping);
      if (self_contact_pressure != 0 && !can.begins_steps)
        refuse("Boundary conditions/Self contact pressure",
               "needs",
               &Capabilities::begins_steps);
      if (obstacles.empty())
        return;
      prm.enter_subsection("Contact");
      const bool penalty = prm.get("Method") == "penalty";
      prm.leave_subsection();
      if (penalty && !can.penalty_contact)
        refuse(obstacles.front().slot + "/Shape",
               "contact with obstacles by a penalty needs",
               &Capabilities::penalty_contact,
               can.taken_away);
      if (!penalty && !can.augmented_lagrangian)
        refuse(obstacles.front().slot + "/Shape",
               "contact with obstacles by the augmented Lagrangian needs",
               &Capabilities::augmented_lagrangian);
    }

    /**
     * 'Self contact pressure = automatic': crushed tetrahedra (triangles)
     * of the invertible model can settle tangled, which elasticity holds
     * (doc/tests.md, inversion recovery), so there self contact is on at
     * twice the shear modulus, where it untangled every one of 33 crushed
     * starts; hexahedra recover by elasticity alone.
     */
    template <int dim>
    void
    resolve_self_contact(const ChosenIntegrator              &integrator,
                         const materials::MaterialParameters &materials,
                         boundary::BoundaryParameters        &boundary,
                         const Triangulation<dim>            &mesh)
    {
      double shear = 0;
      for (unsigned int m = 0; m < materials.model_names.size(); ++m)
        if (materials.model_names[m] == "invertible neo-Hookean")
          shear = std::max(shear, materials.constants[m].mu);
      const bool  takes     = integrator.can.begins_steps;
      const bool  simplices = !mesh.all_reference_cells_are_hyper_cube();
      std::string why
        = shear == 0   ? "no invertible neo-Hookean material"
          : !simplices ? "the invertible model on quadrilaterals or hexahedra, "
                         "which recover by elasticity alone"
          : !takes     ? "integrator '" + integrator.parameters.integrator
                       + "' does not take it"
                   : "twice the shear modulus of the invertible "
                     "neo-Hookean model on triangles or tetrahedra";
      boundary.resolve_self_contact(shear,
                                    shear > 0 && simplices && takes,
                                    why);
    }
  } // namespace


  template <int dim>
  Scene<dim>::Scene(ParameterHandler  &prm,
                    const std::string &parameter_directory)
      : triangulation(parallel_tools::communicator(),
                      Triangulation<dim>::limit_level_difference_at_vertices,
                      /*allow_artificial_cells=*/false,
                      parallel::shared::Triangulation<dim>::partition_metis)
  {
    geometry::GeometryParameters geometry_parameters;
    geometry_parameters.parse_parameters(prm);
    geometry_parameters.resolve_relative_to(parameter_directory);
    geometry::build_triangulation(geometry_parameters, triangulation);

    materials::MaterialParameters material_parameters;
    material_parameters.parse_parameters(prm);
    materials
      = std::make_unique<materials::MaterialSet<dim>>(material_parameters, prm);
    materials->check_covers(triangulation);

    const ChosenIntegrator       integrator(prm);
    boundary::BoundaryParameters boundary_parameters;
    boundary_parameters.parse_parameters(prm);
    {
      // 'Load factor = automatic': the loads of a quasistatic run ramp
      // over it (a manufactured solution's are exact as they are).
      boundary::ManufacturedParameters manufactured_parameters;
      manufactured_parameters.parse_parameters(prm);
      prm.enter_subsection("Time integration");
      const std::string end_time = prm.get("End time");
      prm.leave_subsection();
      boundary_parameters.resolve_load_factor(
        !integrator.can.in_time && !manufactured_parameters.enabled, end_time);
    }
    resolve_self_contact<dim>(integrator,
                              material_parameters,
                              boundary_parameters,
                              triangulation);
    boundary_conditions = std::make_unique<boundary::BoundaryConditions<dim>>(
      boundary_parameters);
    boundary_conditions->check_boundary_ids(triangulation);
    // Every registered kind of tool the file asks for.
    for (const auto &[name, entry] : tool::ToolRegistry<dim>::instance().all())
      if (auto t = entry.create(prm, triangulation))
        tools.emplace(name, std::move(t));

    boundary::ManufacturedParameters manufactured_parameters;
    manufactured_parameters.parse_parameters(prm);
    if (manufactured_parameters.enabled)
      {
        require(Utilities::trim(boundary_parameters.load_factor) == "1",
                "Boundary conditions/Load factor",
                "must be 1 with a manufactured solution (whose body force "
                "and boundary values are exact as they are)");
        require(tools.empty(),
                "Manufactured solution/Enabled",
                "cannot be combined with a tool");
        manufactured = std::make_unique<boundary::ManufacturedSolution<dim>>(
          manufactured_parameters,
          *materials,
          triangulation,
          integrator.can.in_time);
        manufactured->impose_on(*boundary_conditions);
      }

    auto obstacles
      = contact::Obstacle<dim>::create_all(prm, parameter_directory);
    check_integrator_capabilities(prm,
                                  integrator,
                                  boundary_parameters.self_contact_pressure,
                                  obstacles);

    // A tool may hold a part only once it acts, and an obstacle only once
    // the part touches it; the check needs the constraints known up front.
    if (!integrator.can.in_time && tools.empty() && obstacles.empty())
      check_every_part_held();

    solid::FiniteElementParameters fe_parameters;
    fe_parameters.parse_parameters(prm);
    discretization = std::make_unique<solid::Discretization<dim>>(triangulation,
                                                                  fe_parameters,
                                                                  dim);
    solid          = std::make_unique<solid::Solid<dim>>(*discretization,
                                                *materials,
                                                *boundary_conditions);
    if (!obstacles.empty())
      {
        // The penalty scales with the stiffest material's Young's modulus,
        // E = mu (3 lambda + 2 mu) / (lambda + mu).
        double modulus = 0;
        for (const auto &c : material_parameters.constants)
          modulus
            = std::max(modulus,
                       c.mu * (3 * c.lambda + 2 * c.mu) / (c.lambda + c.mu));
        obstacle_contact = std::make_shared<contact::PenaltyContact<dim>>(
          prm, *discretization, std::move(obstacles), modulus);
        solid->add_force_contribution(obstacle_contact);
      }
    if (boundary_parameters.self_contact_pressure > 0)
      solid->add_force_contribution(std::make_shared<contact::SelfContact<dim>>(
        *discretization,
        boundary_parameters.self_contact_pressure,
        boundary_parameters.self_contact_tangent));
    for (auto &[name, t] : tools)
      t->attach(obstacle_contact.get());
    check_initial_data();
  }


  template <int dim>
  void
  Scene<dim>::check_initial_data() const
  {
    VectorType u, v;
    solid->initial_state(u, v);
    require(all_finite(u),
            "Boundary conditions/Initial displacement",
            "is not finite at some node");
    require(all_finite(v),
            "Boundary conditions/Initial velocity",
            "is not finite at some node");
    solid->apply_dirichlet_values(0., u);
    require(all_finite(u),
            "Boundary conditions/Dirichlet",
            "is not finite at some boundary node at t = 0");
  }


  template <int dim>
  void
  Scene<dim>::check_every_part_held() const
  {
    const geometry::MeshParts<dim> parts(triangulation);
    // Per part, the displacement components some Dirichlet face fixes.
    std::vector<std::vector<bool>> fixed(parts.n_parts(),
                                         std::vector<bool>(dim, false));
    for (const auto &cell : triangulation.active_cell_iterators())
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary())
          for (const auto &d : boundary_conditions->dirichlet)
            if (d.id == face->boundary_id())
              for (unsigned int c = 0; c < dim; ++c)
                if (d.mask[c])
                  fixed[parts.part_of_cell[cell->active_cell_index()]][c]
                    = true;

    const char        *axes[3] = {"x", "y", "z"};
    std::ostringstream list;
    unsigned int       n_loose = 0, n_named = 0;
    for (unsigned int p = 0; p < parts.n_parts(); ++p)
      {
        std::string  free;
        unsigned int n_free = 0;
        for (unsigned int c = 0; c < dim; ++c)
          if (!fixed[p][c] && ++n_free)
            free += std::string(free.empty() ? "" : ", ") + axes[c];
        if (n_free == 0)
          continue;
        if (++n_loose > 5)
          continue;
        ++n_named;
        list << (n_named > 1 ? "; " : "") << "part " << p + 1 << " (cell "
             << parts.first_cell[p] << ", centre " << parts.a_point[p] << ") "
             << (n_free == dim ? "held by nothing" : "free along " + free);
      }
    if (n_loose > n_named)
      list << "; and " << n_loose - n_named << " more";
    require(n_loose == 0,
            "Boundary conditions/Dirichlet",
            "a quasistatic solve needs every part of the body held, but "
              + std::to_string(n_loose) + " of its "
              + std::to_string(parts.n_parts())
              + " face-connected parts are not: " + list.str()
              + ". Hold each part in every direction (a Dirichlet boundary "
                "id on it), or integrate in time");
  }


  template <int dim>
  time::State
  Scene<dim>::initial_state() const
  {
    time::State state;
    solid->initial_state(state.u, state.v);
    solid->apply_dirichlet_values(0., state.u);
    return state;
  }


  template <int dim>
  std::string
  Scene<dim>::describe() const
  {
    std::ostringstream s;
    s << triangulation.n_active_cells() << " cells, " << solid->n_dofs()
      << " unknowns, element " << discretization->fe->get_name();
    return s.str();
  }

  template class Scene<1>;
  template class Scene<2>;
  template class Scene<3>;
} // namespace tissuefem
