#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <tissuefem/base/trajectory_table.h>
#include <tissuefem/contact/penalty_contact.h>
#include <tissuefem/tool/haptic_renderer.h>
#include <tissuefem/tool/interface.h>

#include <memory>
#include <string>

namespace tissuefem::tool
{
  using namespace dealii;

  /**
   * An instrument that pushes: one of the scene's rigid obstacles
   * ('Contact/Obstacle k', named by 'Contact tool/Obstacle') in the user's
   * hand. It moves as its obstacle's 'Motion' or 'Motion file' says, or,
   * with a 'Live port', as a live client (a haptic device's driver) sends
   * positions: the obstacle is then translated by d(t), the position minus
   * the first received. After every step it reports the force the tissue
   * exerts on it (minus the obstacle's contact force on the tissue, summed
   * over its contact points and the processes) to tool_force.csv, and the
   * forces a device feels between steps (haptic_renderer.h) to
   * haptic_force.csv and to the live client; the stiffness the device then
   * feels is the secant stiffness observed at the tool, the tissue's and
   * the contact's in series, not the penalty's alone. It holds no vertex,
   * so the mesh may be refined while it works.
   */
  template <int dim>
  class ContactTool : public Interface<dim>
  {
  public:
    /// Declares the 'Contact tool' subsection.
    static void
    declare_parameters(ParameterHandler &prm);

    /// The tool 'Contact tool' asks for, or null if it names no obstacle.
    static std::unique_ptr<Interface<dim>>
    create(ParameterHandler &prm, const Triangulation<dim> &mesh);

    ContactTool(const std::string &obstacle, const HapticParameters &haptic);

    /// Finds its obstacle in @p contact (refuses a name that is not
    /// there, or a live tool whose obstacle has a motion of its own) and,
    /// live, makes it follow the client.
    void
    attach(contact::PenaltyContact<dim> *contact) override;

    bool
    allows_refinement() const override
    {
      return true;
    }

    /// It never changes constraints.
    bool
    due(const double) const override
    {
      return false;
    }
    void
    act(const time::State &, solid::Solid<dim> &) override
    {
    }

    void
    connect(const std::string &directory, const double body_diameter) override;
    bool
    synchronize(const double time) override;
    std::string
    live_end() const override;
    std::vector<double>
    haptic_latency() const override
    {
      return haptic.latency();
    }

    /// The contact force on the tool after a step, and the haptic samples.
    Record<dim>
    record(const time::State           &state,
           solid::Solid<dim>           &solid,
           const contact::Reports<dim> &contact) override;

    std::string
    summary() const override;

  private:
    /// The tool's displacement d(t) from where it started (length units).
    Tensor<1, dim>
    displacement(const double time) const;

    std::string                   obstacle_name;
    contact::PenaltyContact<dim> *contact = nullptr;
    unsigned int                  index   = 0;
    /// The live client's positions.
    TrajectoryTable<dim> table;
    HapticRenderer<dim>  haptic;
    unsigned int         steps_touching = 0, steps = 0;
  };
} // namespace tissuefem::tool
