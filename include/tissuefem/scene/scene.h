#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/distributed/tria_base.h>

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
   * their scenes here, so a scene means the same thing everywhere. METIS
   * gives each MPI process its cells to assemble; every process holds the
   * whole mesh or only its cells and their neighbours, as 'Geometry/Mesh
   * distribution' says (geometry/distribution.h). The checks that need the
   * whole mesh (materials and boundary ids cover it, every part is held)
   * run on it either way, before it is cut.
   *
   * Members are public and built in the order listed; each refers to those
   * before it, so none may be replaced while a later one lives.
   */
  template <int dim>
  class Scene
  {
    /// Owns the mesh `triangulation` refers to (declared first: built
    /// first).
    std::unique_ptr<parallel::TriangulationBase<dim>> mesh;

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

    /// One line for the screen: cells (of all processes), unknowns,
    /// element.
    std::string
    describe() const;

    /// For a distributed mesh, one line for the screen: "mesh distributed:
    /// each of N processes holds at most C of the M cells (its own and the
    /// layer around them)"; empty when every process holds the whole mesh.
    /// Collective.
    std::string
    describe_distribution() const;

    /// The mesh the run computes on: a parallel::shared or a
    /// parallel::fullydistributed triangulation.
    parallel::TriangulationBase<dim>                    &triangulation;
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
     * face-connected part of the body (@p whole, the whole mesh) is held:
     * what to tell the user (one line) if some are not, naming the parts
     * that no Dirichlet boundary holds, or holds in some directions only,
     * with a point of each; empty if all are held.
     */
    std::string
    unheld_parts(const Triangulation<dim> &whole) const;
  };
} // namespace tissuefem
