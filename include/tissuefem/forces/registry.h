#pragma once

#include <deal.II/base/parameter_handler.h>

#include <tissuefem/base/registry.h>
#include <tissuefem/materials/material_set.h>
#include <tissuefem/solid/discretization.h>
#include <tissuefem/solid/force_contribution.h>
#include <tissuefem/time/interface.h>

#include <memory>
#include <string>
#include <vector>

namespace tissuefem::forces
{
  using Capabilities = time::Interface::Capabilities;

  /**
   * What every force contribution derives from. The solid holds its
   * contributions and calls them in its assembly, so the interface is the
   * solid's (solid/force_contribution.h); this folder holds how they are
   * registered and created from a parameter file, which needs the solid
   * and the integrators. The dependencies run one way: forces and contact
   * on solid and time, never back.
   */
  template <int dim>
  using Interface    = solid::ForceContribution<dim>;
  using Augmentation = solid::Augmentation;

  /**
   * What a force contribution may read when the scene creates it, besides
   * its own parameters: the scene's discretization (built before any
   * contribution), its materials, and the integrator the file chose, so
   * that a contribution refuses an integrator that cannot honour it itself
   * (refuse_unless()) instead of the scene knowing every contribution.
   * Only the discretization outlives create(): the other members refer to
   * the scene constructor's locals, so a contribution copies what it
   * keeps of them.
   */
  template <int dim>
  struct SceneData
  {
    /// The parameter file's directory (relative paths of files a
    /// contribution reads are taken from it; empty: the working one).
    const std::string                   &parameter_directory;
    const materials::MaterialParameters &materials;
    const solid::Discretization<dim>    &discretization;
    /// 'Time integration/Integrator' and what it can take as set.
    const std::string  &integrator;
    const Capabilities &can;
    /// Lines for the run's first lines: what a contribution resolved (an
    /// 'automatic' setting) and why, also when it decided to be off.
    std::vector<std::string> &notes;

    /**
     * Throws InputError naming @p parameter unless the integrator has
     * @p needed: "Parameter 'p': <what> Time integration/Integrator = <the
     * integrators that have it> (not '<chosen>': <why>)".
     */
    void
    refuse_unless(bool Capabilities::*needed,
                  const std::string  &parameter,
                  const std::string  &what,
                  const std::string  &why = "") const;

    /// The largest Young's modulus of the materials,
    /// E = mu (3 lambda + 2 mu) / (lambda + mu) (stress units).
    double
    largest_youngs_modulus() const;
  };

  /// The registered integrators that have the capability @p has with their
  /// default settings, as "a, b or c" (for messages).
  std::string
  integrators_with(bool Capabilities::*has);

  /**
   * Force contributions by name. Each kind declares its own parameters;
   * its factory returns null when the file asks for none of it. The scene
   * creates every kind the file asks for, in name order, and hands each to
   * the solid (Solid::add_force_contribution()).
   */
  template <int dim>
  using ContributionRegistry
    = Registry<Interface<dim>, ParameterHandler &, const SceneData<dim> &>;
} // namespace tissuefem::forces

/**
 * Registers the force contribution template @p Class (on dim) under
 * @p name for dim = 1, 2, 3, at the end of its source file. @p Class<dim>
 * has a static declare_parameters(ParameterHandler &) and a static
 * create(ParameterHandler &, const forces::SceneData<dim> &) returning
 * std::unique_ptr<forces::Interface<dim>> (null if not asked for).
 */
#define TISSUEFEM_REGISTER_FORCE_CONTRIBUTION(Class, name, description) \
  namespace                                                             \
  {                                                                     \
    template <int dim>                                                  \
    bool                                                                \
    tissuefem_register_contribution_in()                                \
    {                                                                   \
      ::tissuefem::forces::ContributionRegistry<dim>::instance().add(   \
        name,                                                           \
        description,                                                    \
        &Class<dim>::declare_parameters,                                \
        &Class<dim>::create);                                           \
      return true;                                                      \
    }                                                                   \
    const bool tissuefem_registered_contribution_##Class                \
      = tissuefem_register_contribution_in<1>()                         \
        && tissuefem_register_contribution_in<2>()                      \
        && tissuefem_register_contribution_in<3>();                     \
  }
