#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>
#include <deal.II/grid/tria.h>

#include <tissuefem/base/registry.h>
#include <tissuefem/solid/solid.h>
#include <tissuefem/time/interface.h>

#include <memory>
#include <string>

namespace tissuefem::tool
{
  using namespace dealii;

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

    /// Creates the tool's own files in @p directory (and opens any link to
    /// a device). Called once, after all input has been checked.
    virtual void
    open(const std::string &directory)
      = 0;

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

    /// After a step (every process calls): the force the tissue exerts on
    /// the tool (force units), also written to the tool's own files.
    virtual Tensor<1, dim>
    record(const time::State &state, solid::Solid<dim> &solid) = 0;

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
