#pragma once

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <tissuefem/base/trajectory_table.h>
#include <tissuefem/solid/solid.h>
#include <tissuefem/time/interface.h>
#include <tissuefem/tool/haptic_renderer.h>
#include <tissuefem/tool/interface.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace tissuefem::tool
{
  using namespace dealii;

  /// The vertices of @p mesh within @p radius of @p point (length units):
  /// what a grasp holds.
  template <int dim>
  std::vector<unsigned int>
  vertices_within(const Triangulation<dim> &mesh,
                  const Point<dim>         &point,
                  const double              radius);

  /// The 'Tool' subsection.
  struct ToolParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    bool        enabled = false;
    std::string grasp_point, trajectory, trajectory_file;
    double      radius = 0, grasp_time = 0, release_time = 0;
    /// Haptic rate, force extrapolation, live port.
    HapticParameters haptic;
  };

  /**
   * The user's hand (Jeffrey section 2, the "laparoscopic surgery
   * workstation"): at 'Grasp time' the vertices within 'Grasp radius' of
   * 'Grasp point' (reference coordinates) are held; their displacement then
   * follows the tool, u = u_grasp + d(t) - d(t_grasp), with d the
   * 'Trajectory' expression of t or the positions of a recorded
   * 'Trajectory file'; at 'Release time' they are let go.
   *
   * After every simulation step it reports the force the tissue exerts on
   * the tool (minus the reaction at the held vertices).
   * Between steps a haptic device needs forces at 'Haptic rate': they are
   * extrapolated from the steps so far, either linearly in time or
   * linearly in the tool's position with a stiffness estimated from the
   * observed force and position changes (a Broyden secant update, the
   * data-driven counterpart of Picinbono's force extrapolation from the
   * contact nodes' stiffness), and reported with their error against the force
   * the simulation then computed (interpolated linearly between its steps to
   * the haptic instant).
   */
  template <int dim>
  class GraspTool : public Interface<dim>
  {
  public:
    /// Declares the 'Tool' subsection.
    static void
    declare_parameters(ParameterHandler &prm);

    /// The tool the 'Tool' subsection of @p prm describes, or null if it
    /// sets no 'Grasp point'.
    static std::unique_ptr<Interface<dim>>
    create(ParameterHandler &prm, const Triangulation<dim> &mesh);

    GraspTool(const ToolParameters &parameters, const Triangulation<dim> &mesh);

    /// Grasps or releases if the time has come (call before each step).
    /// Returns whether the constraints changed: the caller must have reset
    /// its linear solvers before and tell the integrator after.
    bool
    due(const double time) const override;
    void
    act(const time::State &state, solid::Solid<dim> &solid) override;

    /// In live mode, starts listening for the client (the port goes to
    /// @p directory/live_port).
    void
    connect(const std::string &directory, const double body_diameter) override;

    /**
     * Live mode: receives positions from the client until they cover
     * @p time (the link's thread has answered each with the force model of
     * the last record()); the step then starts.
     * Returns false when the session ended before (the run should stop;
     * live_end() says why). Without a live client: true at once.
     */
    bool
    synchronize(const double time) override;
    /// Why the live session ended (empty while it goes on).
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

    /// The force after a step (every process calls), and the haptic
    /// forces extrapolated for the instants since the previous step.
    Record<dim>
    record(const time::State           &state,
           solid::Solid<dim>           &solid,
           const contact::Reports<dim> &contact) override;

    /// The haptic report: updates, share within the budget, extrapolation
    /// error.
    std::string
    summary() const override;

    /// The tool's displacement d(t) (length units).
    Tensor<1, dim>
    displacement(const double time) const;

    std::optional<Grasp<dim>>
    grasp(const double time) const override;

  private:
    ToolParameters                       parameters;
    Point<dim>                           grasp_point;
    std::vector<unsigned int>            vertices;
    std::unique_ptr<FunctionParser<dim>> trajectory;
    /// Recorded or live positions (or none, with 'Trajectory').
    TrajectoryTable<dim> table;
    bool                 holding = false, released = false;
    /// The force of the tissue on it at the last record().
    Tensor<1, dim> last_force;
    double         grasp_time_actual = 0;
    /// The forces the device feels between steps.
    HapticRenderer<dim> haptic;
  };
} // namespace tissuefem::tool
