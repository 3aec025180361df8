#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>
#include <deal.II/grid/tria.h>

#include <tissuefem/base/registry.h>
#include <tissuefem/contact/penalty_contact.h>
#include <tissuefem/solid/solid.h>
#include <tissuefem/time/interface.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace tissuefem::tool
{
  using namespace dealii;

  /**
   * What a view shows of a tool that holds vertices (the live view's
   * arrow): where it grasped, how far it moved them since, and the force
   * of the tissue on it after the last record().
   */
  template <int dim>
  struct Grasp
  {
    /// The grasped point (reference coordinates, length units).
    Point<dim> point;
    /// The held vertices' displacement since the grasp (length units).
    Tensor<1, dim> displacement;
    /// The force the tissue exerts on the tool (force units).
    Tensor<1, dim> force;
  };

  /**
   * What a tool reports after a step. The 'tool force' postprocessor writes
   * it (tool_force.csv, haptic_force.csv, the summary file); a tool writes
   * no files itself.
   */
  template <int dim>
  struct Record
  {
    /// The tool's displacement from where it started, d(t) (length units).
    Tensor<1, dim> position;
    /// The force the tissue exerts on the tool (force units).
    Tensor<1, dim> force;
    /// Whether the tool acts on the tissue (holds it, or touches it).
    bool engaged = false;

    /// A force sent to a haptic device between two steps.
    struct HapticSample
    {
      /// When it was due (time units).
      double time;
      /// The force extrapolated from the steps before (force units).
      Tensor<1, dim> force;
      /// Its distance from the force the simulation then computed,
      /// interpolated linearly between the steps to @p time (force units).
      double error;
    };
    /// The haptic forces due in (previous step, this step], in order of
    /// time; empty for a tool that drives no device.
    std::vector<HapticSample> haptic;
  };


  /**
   * A surgical instrument acting on the body: it changes the solid's
   * constraints (or, later, its loads) at moments of its choosing, and
   * reports the force the tissue exerts on it after every step.
   *
   * Each kind is one file pair that derives from this class, declares its
   * own parameters and registers itself with TISSUEFEM_REGISTER_TOOL. A
   * scene creates every registered kind its parameter file asks for (the
   * factory returns null for a kind not asked for).
   *
   * Constraint changes go through the solid (Solid::hold, Solid::release),
   * which announces them on Solid::signals; a tool calls nobody else.
   */
  template <int dim>
  class Interface
  {
  public:
    virtual ~Interface() = default;

    /// Whether act() has something to do before the step from @p time.
    virtual bool
    due(const double time) const = 0;

    /// Changes the constraints (grasps, releases) for the state @p state.
    virtual void
    act(const time::State &state, solid::Solid<dim> &solid)
      = 0;

    /**
     * Called once by the scene after it has set up contact with its
     * obstacles (@p contact; null without obstacles), before anything runs:
     * a tool that is an obstacle finds it there (and may move it).
     */
    virtual void
    attach(contact::PenaltyContact<dim> *contact)
    {
      (void)contact;
    }

    /// Whether the tool keeps working when the mesh is refined (a tool that
    /// holds the initial mesh's vertices does not).
    virtual bool
    allows_refinement() const
    {
      return false;
    }

    /// What it holds at @p time, for a view (none: it holds nothing, or
    /// it is not a grasping tool).
    virtual std::optional<Grasp<dim>>
    grasp(const double time) const
    {
      (void)time;
      return std::nullopt;
    }

    /// Whether a checkpoint may be written now with this tool in the
    /// scene: a tool whose motion, holds or device link a checkpoint does
    /// not keep may not.
    virtual bool
    checkpointable() const
    {
      return false;
    }

    /// Whether a device on a live port moves it (its positions carry the
    /// device's clock, so the run's time cannot go back).
    virtual bool
    follows_device() const
    {
      return false;
    }

    /// Opens any link to a device (which may leave a file in
    /// @p directory, the output directory), with limits on what the device
    /// may ask scaled by @p body_diameter (length units). Called once,
    /// after all input has been checked.
    virtual void
    connect(const std::string & /*directory*/, const double /*body_diameter*/)
    {
    }

    /**
     * Waits until the tool's motion is known up to @p time (a live device);
     * returns false if it never will be (the session ended: the run stops,
     * live_end() says why).
     */
    virtual bool
    synchronize(const double /*time*/)
    {
      return true;
    }

    /// Why a live session ended (empty while it goes on, or without one).
    virtual std::string
    live_end() const
    {
      return {};
    }

    /// After a step (every process calls): where the tool is, the force on
    /// it, and the haptic forces sent since the previous step. @p contact:
    /// each obstacle's report at @p state (empty without obstacles).
    virtual Record<dim>
    record(const time::State           &state,
           solid::Solid<dim>           &solid,
           const contact::Reports<dim> &contact)
      = 0;

    /// A live device's recent answer latency: median and 99th percentile
    /// (ms), on process 0; empty without one.
    virtual std::vector<double>
    haptic_latency() const
    {
      return {};
    }

    /// The end-of-run report (one or more lines, no trailing newline).
    virtual std::string
    summary() const = 0;
  };

  /// Tools by name; the factory returns null if @p prm asks for none of
  /// this kind.
  template <int dim>
  using ToolRegistry
    = Registry<Interface<dim>, ParameterHandler &, const Triangulation<dim> &>;
} // namespace tissuefem::tool

/**
 * Registers the tool template @p Tool (on dim) under @p name for dim = 1, 2,
 * 3, at the end of its source file. @p Tool<dim> has a static
 * declare_parameters(ParameterHandler &) and a static
 * create(ParameterHandler &, const Triangulation<dim> &) returning
 * std::unique_ptr<Interface<dim>> (null if not asked for).
 */
#define TISSUEFEM_REGISTER_TOOL(Tool, name, description)                   \
  namespace                                                                \
  {                                                                        \
    template <int dim>                                                     \
    bool                                                                   \
    tissuefem_register_tool_in()                                           \
    {                                                                      \
      ::tissuefem::tool::ToolRegistry<dim>::instance().add(                \
        name,                                                              \
        description,                                                       \
        &Tool<dim>::declare_parameters,                                    \
        &Tool<dim>::create);                                               \
      return true;                                                         \
    }                                                                      \
    const bool tissuefem_registered_tool_##Tool                            \
      = tissuefem_register_tool_in<1>() && tissuefem_register_tool_in<2>() \
        && tissuefem_register_tool_in<3>();                                \
  }
