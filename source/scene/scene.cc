#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/forces/registry.h>
#include <tissuefem/geometry/distribution.h>
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

  } // namespace


  template <int dim>
  void
  Scene<dim>::declare_parameters(ParameterHandler &prm)
  {
    tool::ToolRegistry<dim>::instance().declare_parameters(prm);
    boundary::ManufacturedParameters::declare_parameters(prm);
    forces::ContributionRegistry<dim>::instance().declare_parameters(prm);
  }


  namespace
  {
    /// Rayleigh damping needs an integrator that applies it: others would
    /// ignore it unseen. (Each force contribution checks what it needs.)
    void
    check_rayleigh_damping(const ChosenIntegrator &integrator)
    {
      for (const auto &[name, value] :
           {std::pair("mass", integrator.parameters.rayleigh_mass),
            std::pair("stiffness", integrator.parameters.rayleigh_stiffness)})
        if (value != 0 && !integrator.can.rayleigh_damping)
          throw InputError(
            std::string("Parameter 'Time integration/Rayleigh ") + name
            + " damping': must be 0 unless Time integration/Integrator = "
            + forces::integrators_with(&Capabilities::rayleigh_damping)
            + " (not '" + integrator.parameters.integrator + "')");
    }


    /// How 'Geometry/Mesh distribution' spreads the mesh; one process
    /// always holds all of it.
    template <int dim>
    geometry::Distribution
    distribution_of(ParameterHandler &prm)
    {
      geometry::GeometryParameters parameters;
      parameters.parse_parameters(prm);
      if (parallel_tools::n_processes() == 1)
        return geometry::Distribution::shared;
      // In 1D a fully distributed mesh takes the ends of each process's
      // cells for boundary points, with ids of their own.
      require(dim > 1
                || parameters.distribution == geometry::Distribution::shared,
              "Geometry/Mesh distribution",
              "'distributed' needs a 2D or 3D body (a bar's mesh is small: "
              "use 'shared')");
      return parameters.distribution;
    }
  } // namespace


  template <int dim>
  Scene<dim>::Scene(ParameterHandler  &prm,
                    const std::string &parameter_directory)
      : mesh(geometry::make_parallel_mesh<dim>(distribution_of<dim>(prm)))
      , triangulation(*mesh)
  {
    // The whole mesh: the one the run computes on, or, when that will hold
    // each process's cells only, a serial mesh every process builds alike,
    // checks, cuts and frees before any unknown is numbered (`whole` is not
    // used after the cut).
    const bool cut = !geometry::holds_whole_mesh<dim>(triangulation);
    std::unique_ptr<Triangulation<dim>> serial_mesh;
    if (cut)
      serial_mesh = std::make_unique<Triangulation<dim>>(
        Triangulation<dim>::limit_level_difference_at_vertices);
    const Triangulation<dim> &whole = cut ? *serial_mesh : triangulation;
    {
      geometry::GeometryParameters geometry_parameters;
      geometry_parameters.parse_parameters(prm);
      geometry_parameters.resolve_relative_to(parameter_directory);
      geometry::build_triangulation(geometry_parameters,
                                    cut ? *serial_mesh : triangulation);
    }

    materials::MaterialParameters material_parameters;
    material_parameters.parse_parameters(prm);
    materials
      = std::make_unique<materials::MaterialSet<dim>>(material_parameters, prm);
    materials->check_covers(whole);

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
    boundary_conditions = std::make_unique<boundary::BoundaryConditions<dim>>(
      boundary_parameters);
    boundary_conditions->check_boundary_ids(whole);
    boundary::ManufacturedParameters manufactured_parameters;
    manufactured_parameters.parse_parameters(prm);
    if (manufactured_parameters.enabled)
      {
        require(Utilities::trim(boundary_parameters.load_factor) == "1",
                "Boundary conditions/Load factor",
                "must be 1 with a manufactured solution (whose body force "
                "and boundary values are exact as they are)");
        manufactured = std::make_unique<boundary::ManufacturedSolution<dim>>(
          manufactured_parameters, *materials, whole, integrator.can.in_time);
        manufactured->impose_on(*boundary_conditions);
      }
    // Whether every part is held (the manufactured solution's boundary
    // values included) matters only once the tools and force contributions
    // are known (below), but is asked of the whole mesh now.
    const std::string loose
      = integrator.can.in_time ? std::string() : unheld_parts(whole);
    // Nothing below needs the whole mesh.
    if (cut)
      {
        geometry::distribute(*serial_mesh, triangulation);
        serial_mesh.reset();
      }

    // Every registered kind of tool the file asks for (each refuses a
    // distributed mesh if it needs the whole one).
    for (const auto &[name, entry] : tool::ToolRegistry<dim>::instance().all())
      if (auto t = entry.create(prm, triangulation))
        tools.emplace(name, std::move(t));
    require(!manufactured || tools.empty(),
            "Manufactured solution/Enabled",
            "cannot be combined with a tool");

    check_rayleigh_damping(integrator);
    if (!integrator.can.whole_mesh_parameter.empty())
      geometry::require_whole_mesh<dim>(triangulation,
                                        integrator.can.whole_mesh_parameter,
                                        "this setting colours the unknowns "
                                        "of the whole mesh");

    solid::FiniteElementParameters fe_parameters;
    fe_parameters.parse_parameters(prm);
    discretization = std::make_unique<solid::Discretization<dim>>(triangulation,
                                                                  fe_parameters,
                                                                  dim);
    solid          = std::make_unique<solid::Solid<dim>>(
      *discretization,
      *materials,
      *boundary_conditions,
      solid::formulations::create<dim>(materials->formulation(), prm));
    // Every registered kind of force contribution the file asks for.
    const forces::SceneData<dim> data{parameter_directory,
                                      material_parameters,
                                      *discretization,
                                      integrator.parameters.integrator,
                                      integrator.can,
                                      notes};
    bool                         held = false;
    for (const auto &[name, entry] :
         forces::ContributionRegistry<dim>::instance().all())
      if (std::shared_ptr<forces::Interface<dim>> c = entry.create(prm, data))
        {
          held = held || c->may_hold_body();
          if (const auto p
              = std::dynamic_pointer_cast<contact::PenaltyContact<dim>>(c))
            obstacle_contact = p;
          contributions.emplace(name, c);
          solid->add_force_contribution(c);
        }

    // A tool may hold a part only once it acts, and an obstacle only once
    // the part touches it; the check needs the constraints known up front.
    if (!integrator.can.in_time && tools.empty() && !held)
      require(loose.empty(), "Boundary conditions/Dirichlet", loose);
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
  std::string
  Scene<dim>::unheld_parts(const Triangulation<dim> &whole) const
  {
    const geometry::MeshParts<dim> parts(whole);
    // Per part, the displacement components some Dirichlet face fixes.
    std::vector<std::vector<bool>> fixed(parts.n_parts(),
                                         std::vector<bool>(dim, false));
    for (const auto &cell : whole.active_cell_iterators())
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
    if (n_loose == 0)
      return {};
    return "a quasistatic solve needs every part of the body held, but "
           + std::to_string(n_loose) + " of its "
           + std::to_string(parts.n_parts())
           + " face-connected parts are not: " + list.str()
           + ". Hold each part in every direction (a Dirichlet boundary id on "
             "it), or integrate in time";
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
    s << triangulation.n_global_active_cells() << " cells, " << solid->n_dofs()
      << " unknowns, element " << discretization->fe->get_name()
      << ", formulation '" << materials->formulation() << "'";
    return s.str();
  }

  template <int dim>
  std::string
  Scene<dim>::describe_distribution() const
  {
    if (geometry::holds_whole_mesh<dim>(triangulation))
      return {};
    // Own and ghost cells; not the artificial ones a refined mesh keeps as
    // the parents' other children, which hold nothing.
    unsigned int held = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      held += cell->is_artificial() ? 0 : 1;
    const unsigned int most
      = Utilities::MPI::max(held, triangulation.get_communicator());
    std::ostringstream s;
    s << "mesh distributed: each of " << parallel_tools::n_processes()
      << " processes holds at most " << most << " of "
      << triangulation.n_global_active_cells()
      << " cells (its own and the layer around them)";
    return s.str();
  }


  template class Scene<1>;
  template class Scene<2>;
  template class Scene<3>;
} // namespace tissuefem
