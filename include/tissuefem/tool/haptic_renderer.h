#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <tissuefem/base/trajectory_table.h>
#include <tissuefem/tool/interface.h>
#include <tissuefem/tool/live_link.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace tissuefem::tool
{
  using namespace dealii;

  /**
   * The entries every tool that drives a haptic device declares in its own
   * subsection: 'Haptic rate', 'Force extrapolation', 'Haptic budget',
   * 'Live port' and 'Live timeout'.
   */
  struct HapticParameters
  {
    /// Declares the entries in the subsection @p prm is in.
    static void
    declare_parameters(ParameterHandler &prm);
    /// Reads them from the subsection @p prm is in, named @p section in
    /// messages; checks them only if @p check (the tool is asked for).
    void
    parse_parameters(ParameterHandler  &prm,
                     const std::string &section,
                     const bool         check);

    double      rate = 500, budget = 0.002;
    std::string extrapolation = "position";
    /// -1: no live client; else the loopback port (0: any free one).
    int    live_port    = -1;
    double live_timeout = 5;
    /// 'Live position limit' and 'Live jump limit' (length units; 0:
    /// from the body's diameter).
    double position_limit = 0, jump_limit = 0;
    /// 'Live reserved core'.
    bool reserve_core = true;
  };


  /**
   * What a haptic device feels between simulation steps, shared by every
   * tool (haptic rendering): the steps give the force on the tool at their
   * times; a device needs it at 'Haptic rate'. The force at a haptic
   * instant tau after the last step t_n is extrapolated, either linearly in
   * time from the last two steps, or linearly in the tool's position,
   *
   *   f(tau) = f_n + S (d(tau) - d(t_n)),
   *
   * with S a secant stiffness of the tissue at the tool, estimated from the
   * observed changes of force and position by Broyden's update (the
   * data-driven counterpart of Picinbono's extrapolation from the contact
   * nodes' stiffness, Jeffrey section 4.4). Each sample is reported with its
   * error against the force the simulation then computed (interpolated
   * linearly between its steps to tau).
   *
   * In live mode ('Live port' >= 0) it owns the link to the device
   * (live_link.h): positions arrive into a trajectory table the tool follows,
   * and the link's thread answers each at once with the model above.
   */
  template <int dim>
  class HapticRenderer
  {
  public:
    /// @p displacement is the tool's displacement d(t) (length units).
    HapticRenderer(const HapticParameters                     &parameters,
                   std::function<Tensor<1, dim>(const double)> displacement);

    /// Opens the live link (its port goes to @p directory/live_port), if
    /// asked for, with 'Live position limit' and 'Live jump limit' (0:
    /// @p body_diameter and a tenth of it).
    void
    connect(const std::string &directory, const double body_diameter);

    /// Whether positions come from a live client.
    bool
    live() const
    {
      return parameters.live_port >= 0;
    }

    /// Live mode: appends the client's positions to @p table until they
    /// cover @p time; false when the session ended first. Otherwise true.
    bool
    synchronize(const double time, TrajectoryTable<dim> &table);

    /// Why the live session ended (empty while it goes on, or without one).
    std::string
    live_end() const;

    /**
     * After a step at @p time, where the tool's force is @p force and it
     * is @p engaged (holds or touches the tissue): the haptic samples due
     * since the previous step, extrapolated from the steps before. Updates
     * the model the next samples and the live answers use; a step at
     * which the tool was not engaged, before or now, resets it (a grasp, a
     * release, a first touch are jumps, not trends).
     */
    std::vector<typename Record<dim>::HapticSample>
    update(const double time, const Tensor<1, dim> &force, const bool engaged);

    /// Live: the latency of the device's recent answers (median and 99th
    /// percentile, ms; LiveLink::recent_latency()); else empty.
    std::vector<double>
    latency() const
    {
      return link ? link->recent_latency() : std::vector<double>();
    }

    /// 'haptic: ... updates ..., extrapolation error ...' and, live, the
    /// device's report.
    std::string
    summary() const;

  private:
    /// The force at @p tau extrapolated from the last step; 0 unless the
    /// tool is @p engaged (holds or touches) at the step that ends after
    /// @p tau.
    Tensor<1, dim>
    extrapolated_force(const double tau, const bool engaged) const;

    HapticParameters                            parameters;
    std::function<Tensor<1, dim>(const double)> displacement;
    std::unique_ptr<LiveLink>                   link;

    std::optional<double> last_time;
    Tensor<1, dim>        last_force, last_position, rate;
    /// Tool motions the secant stiffness learns from are longer than this
    /// (length units; a millionth of the body's diameter, set by connect()).
    double         smallest_motion = 0;
    Tensor<2, dim> stiffness;
    bool           have_rate = false, engaged_at_last = false;
    double         next_time = 0;
    unsigned int   updates = 0, within_budget = 0;
    double         max_error = 0, sum_error = 0, max_force = 0;
  };
} // namespace tissuefem::tool
