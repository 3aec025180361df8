#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <tissuefem/base/trajectory_table.h>
#include <tissuefem/contact/penalty_contact.h>
#include <tissuefem/tool/haptic_renderer.h>
#include <tissuefem/tool/interface.h>
#include <tissuefem/tool/mouse_motion.h>

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
   *
   * In a run with a live view and without a live device, the page's mouse
   * moves it too: the offset the page asks (request_move(), on process 0;
   * at most the body's diameter) is added to its obstacle's own motion,
   * reached by at most a tenth of the diameter per step (mouse_motion.h),
   * and kept when the page lets go.
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

    /// The tool pushing with the obstacle named @p obstacle; @p mouse:
    /// whether a live view's mouse may move it.
    ContactTool(const std::string      &obstacle,
                const HapticParameters &haptic,
                const bool              mouse = false);

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
    bool
    follows_device() const override
    {
      return haptic.live();
    }

    /// The contact force on the tool after a step, and the haptic samples.
    Record<dim>
    record(const time::State           &state,
           solid::Solid<dim>           &solid,
           const contact::Reports<dim> &contact) override;

    std::string
    summary() const override;

    /// Its obstacle's index among the scene's obstacles.
    unsigned int
    obstacle() const
    {
      return index;
    }

    /// Whether the live view's mouse moves it.
    bool
    follows_mouse() const
    {
      return mouse;
    }

    /// Process 0: the page asks the tool to be moved by @p offset from its
    /// own motion (length units). Returns why not (empty: taken, from the
    /// next step on).
    std::string
    request_move(const Tensor<1, dim> &offset);

    /// The mouse's offset at @p time (length units).
    Tensor<1, dim>
    mouse_offset(const double time) const
    {
      return (*motion)(time);
    }

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
    /// The live view's mouse: whether it may move the tool, the offset it
    /// asked (process 0) and the offset's motion (shared with the
    /// obstacle's follower, which may outlive the tool).
    bool                              mouse = false;
    Tensor<1, dim>                    asked_offset;
    std::shared_ptr<MouseMotion<dim>> motion
      = std::make_shared<MouseMotion<dim>>();
    /// Where its own motion starts (with the mouse: pose(0) moves with it).
    Tensor<1, dim> start;
  };
} // namespace tissuefem::tool
