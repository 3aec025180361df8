#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/distributed/shared_tria.h>

#include <tissuefem/boundary/boundary_conditions.h>
#include <tissuefem/boundary/manufactured_solution.h>
#include <tissuefem/contact/penalty_contact.h>
#include <tissuefem/geometry/geometry.h>
#include <tissuefem/materials/material_set.h>
#include <tissuefem/solid/discretization.h>
#include <tissuefem/solid/solid.h>
#include <tissuefem/tool/interface.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace tissuefem
{
  using namespace dealii;

  /**
   * Everything a parameter file says about the body and what acts on it:
   * the mesh (Geometry), the materials, the loads and constraints (Boundary
   * conditions, an optional manufactured solution, an optional tool), the
   * discretization and the solid that assembles its operators. A scene is
   * built from the parameters and validated once, in the constructor: after
   * it, every input error has been reported (as an InputError naming the
   * parameter) and no file has been written.
   *
   * The run loop (problems::Elasticity), the benchmarks, the studies'
   * children (which run the elasticity problem) and the unit tests all build
   * their scenes here, so a scene means the same thing everywhere. The mesh
   * is shared by all MPI processes (parallel::shared::Triangulation,
   * partitioned by METIS); each process assembles its own cells.
   *
   * Members are public and built in the order listed; each refers to those
   * before it, so none may be replaced while a later one lives.
   */
  template <int dim>
  class Scene
  {
  public:
    /// Declares the subsections only a scene reads (the tools', Manufactured
    /// solution, the force contributions'); the others are shared with other
    /// problems and declared by the application.
    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * Builds and validates the scene @p prm describes. Relative mesh paths
     * are taken from @p parameter_directory (the parameter file's
     * directory; empty: the working directory).
     */
    explicit Scene(ParameterHandler  &prm,
                   const std::string &parameter_directory = "");

    /// The initial state: displacement and velocity of 'Boundary
    /// conditions', with the Dirichlet values of t = 0 applied.
    time::State
    initial_state() const;

    /// One line for the screen: cells, unknowns, element.
    std::string
    describe() const;

    parallel::shared::Triangulation<dim>                 triangulation;
    std::unique_ptr<materials::MaterialSet<dim>>         materials;
    std::unique_ptr<boundary::BoundaryConditions<dim>>   boundary_conditions;
    std::unique_ptr<boundary::ManufacturedSolution<dim>> manufactured;
    std::unique_ptr<solid::Discretization<dim>>          discretization;
    std::unique_ptr<solid::Solid<dim>>                   solid;
    /// The tools the file asks for (none, one, or one of each registered
    /// kind), by their registered names.
    std::map<std::string, std::unique_ptr<tool::Interface<dim>>> tools;
    /// The registered force contributions the file asks for (contact with
    /// obstacles, self contact), by name, each also handed to the solid.
    std::map<std::string, std::shared_ptr<forces::Interface<dim>>>
      contributions;
    /// Of those, contact with the rigid obstacles of 'Contact' (none:
    /// null), which tools push and outputs report.
    std::shared_ptr<contact::PenaltyContact<dim>> obstacle_contact;
    /// What the contributions resolved, for the run's first lines.
    std::vector<std::string> notes;

  private:
    /// Initial and boundary data must be finite where they are used.
    void
    check_initial_data() const;

    /**
     * A quasistatic solve (no inertia) has a unique answer only if every
     * face-connected part of the body is held: throws InputError (one
     * line, before any output) naming the parts that no Dirichlet boundary
     * holds, or holds in some directions only, with a point of each.
     */
    void
    check_every_part_held() const;
  };
} // namespace tissuefem
