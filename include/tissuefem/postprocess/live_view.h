#pragma once

#include <tissuefem/output/boundary_surface.h>
#include <tissuefem/output/obstacle_view.h>
#include <tissuefem/output/view_server.h>
#include <tissuefem/postprocess/interface.h>

#include <boost/signals2/connection.hpp>

#include <chrono>
#include <deque>
#include <memory>
#include <string>
#include <vector>

namespace tissuefem::tool
{
  template <int dim>
  class MouseGrasp;
  template <int dim>
  class ContactTool;
} // namespace tissuefem::tool

namespace tissuefem::postprocess
{
  /**
   * The live view ('Output/Live view'): a web page served by the run
   * itself (output::ViewServer, on process 0) that shows the deformed
   * surface as the run goes, coloured by a field the page picks, with
   * charts of the step's wall time against the real-time budget, the
   * simulated time per wall-clock second and the energies, and controls
   * (play, pause, one step, pace to the wall clock or as fast as it can).
   *
   * The run never waits for a page: after a step, if a page is open and a
   * frame is due ('Frame rate'), the surface's displacements (and the
   * picked field, averaged from the cells around each vertex) are gathered
   * from every process and handed to the server, which sends each page the
   * newest frame it can take. The topology is sent once, and again after a
   * mesh change (the triangulation's change signal).
   *
   * What pages send, and what the run does with it (text commands, from
   * the driving page): 'pause', 'play', 'step' (one step, then pause),
   * 'reset' (the run starts again from t = 0: ResetRequest),
   * 'pace wall' / 'pace fast', 'field NAME', and for the mouse tool
   * (tool/mouse_grasp.h) 'grasp X Y Z', 'drag DX DY DZ', 'release', and for
   * the contact tool (tool/contact_tool.h) 'tool DX DY DZ'. Pausing and
   * pacing happen in wait(), after a step's outputs and timed apart from
   * them, on process 0; the others wait at the next collective operation. A
   * page closing while the run is paused lets it go on.
   *
   * Messages (little-endian) are documented in doc/live_view.md.
   */
  template <int dim>
  class LiveView : public Interface<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    explicit LiveView(ParameterHandler &prm);
    ~LiveView() override;

    /// Checks the parameters against the scene (a surface needs dim >= 2).
    void
    initialize(const Context<dim> &c) override;

    /// Starts the server and writes its address to <directory>/live_view.
    void
    open() override;

    void
    restore(const std::vector<std::string> &lines) override;

    void
    execute(const Step<dim> &step) override;

    /// Process 0: waits while paused, then paces to the wall clock.
    void
    wait(const time::State &state) override;

    void
    finish(const time::State &state,
           const RunTotals   &totals,
           output::RunRecord &record) override;

    /// Tells the pages why the run stopped, and closes them.
    void
    abort(const std::string &what) override;

  private:
    /// 'Port' (-1: no live view), 'Address', 'Frame rate', 'Wait for page'.
    int         port = -1;
    std::string address;
    double      frame_rate = 60, wait_for_page = 0;
    /// Pacing to the wall clock (else as fast as it can), and paused.
    bool pace_wall = true, paused = false, step_once = false;
    /// Root: the page asked to start again from t = 0.
    bool reset_due = false;
    /// The field the pages colour by (index into field_names).
    unsigned int             field = 0;
    std::vector<std::string> field_names;
    /// What the greeting names: integrator, models, time step, budget.
    std::string integrator, models;
    /// Why the mouse cannot grasp in this run (empty: it can).
    std::string mouse_unavailable;
    double      time_step = 0, budget = 0;

    output::ViewServer::Settings                  settings;
    std::unique_ptr<output::ViewServer>           server;
    std::unique_ptr<output::BoundarySurface<dim>> surface;
    std::unique_ptr<output::ObstacleView<dim>>    obstacles;
    /// The scene's contact tool (null: none), which 'tool' commands move.
    tool::ContactTool<dim>               *contact_tool = nullptr;
    boost::signals2::scoped_connection    mesh_changed;
    bool                                  topology_sent = false;
    unsigned int                          frames        = 0;
    std::chrono::steady_clock::time_point last_frame;
    /// Pacing: wall clock and simulated time when pacing started.
    std::chrono::steady_clock::time_point pace_wall_origin;
    double                                pace_time_origin = 0;
    /// For the simulated time per wall-clock second: (wall-clock seconds
    /// since the start, simulated time) of the frames of the last second.
    std::chrono::steady_clock::time_point run_start;
    std::deque<std::pair<double, double>> recent;

    /// Root: applies the driving page's commands.
    void
    apply_commands(const double time);
    /// The scene's mouse tool (null: none, mouse_unavailable says why).
    tool::MouseGrasp<dim> *
    mouse() const;
    /// Root: asks for a reset (the run starts again at the next wait());
    /// returns why not (empty: asked).
    std::string
    reset_refusal();
    /// Root: simulated time paces from @p time and from now on.
    void
    restart_pacing(const double time);
    /// Root: sends @p last_message to every page, closes the server and
    /// prints its last log lines.
    void
    close_with(const std::string &last_message);
    /// Root: passes 'grasp X Y Z', 'drag DX DY DZ' or 'release' to the
    /// mouse tool, 'tool DX DY DZ' (the offset from its own motion) to the
    /// contact tool; returns why not (empty: passed on).
    std::string
    mouse_command(const std::string &verb, const std::string &argument);
    /// Collective: builds and sends the topology (root sends).
    void
    send_topology();
    /// Collective: gathers the surface's values and sends a frame.
    void
    send_frame(const Step<dim> &step, const double frame_seconds);
    /// Root: waits while paused, then paces to the wall clock.
    void
    hold(const double time);
    /// Prints the server's log lines (root).
    void
    print_log();
    /// The text message each page gets first.
    std::string
    greeting() const;
  };
} // namespace tissuefem::postprocess
