#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_tools.h>

#include <tissuefem/base/interruption.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/base/reset_request.h>
#include <tissuefem/geometry/distribution.h>
#include <tissuefem/output/obstacle_view.h>
#include <tissuefem/output/output_files.h>
#include <tissuefem/output/wire_format.h>
#include <tissuefem/postprocess/live_view.h>
#include <tissuefem/solid/quantities.h>
#include <tissuefem/tool/contact_tool.h>
#include <tissuefem/tool/mouse_grasp.h>

#include <cmath>
#include <sstream>
#include <thread>

#ifndef TISSUEFEM_WEB_DIRECTORY
#define TISSUEFEM_WEB_DIRECTORY "web"
#endif

namespace tissuefem::postprocess
{
  using output::json_number;
  using output::put;
  using output::put_all;

  namespace
  {
    using Clock = std::chrono::steady_clock;

    double
    seconds_since(const Clock::time_point start)
    {
      return std::chrono::duration<double>(Clock::now() - start).count();
    }
  } // namespace


  template <int dim>
  void
  LiveView<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.enter_subsection("Live view");
    prm.declare_entry(
      "Port",
      "-1",
      Patterns::Integer(-1, 65535),
      "A web page showing the run as it goes (open the printed address in "
      "a browser): the deformed surface coloured by a field, charts of the "
      "step's wall time and energies, play, pause, one step. -1 (default): "
      "none; 0: any free port; else this TCP port. The address is printed "
      "and written to <Output directory>/live_view. The command-line "
      "option --view sets 0.");
    prm.declare_entry("Address",
                      "127.0.0.1",
                      Patterns::Anything(),
                      "The IP address the page is served on: 127.0.0.1 "
                      "(default) serves this machine only; any other "
                      "address (0.0.0.0: every interface) lets other "
                      "machines see and drive the run, with a warning.");
    prm.declare_entry("Frame rate",
                      "60",
                      Patterns::Double(1, 240),
                      "At most this many frames per second go to a page "
                      "(1/s); a page that cannot take them all skips to the "
                      "newest.");
    prm.declare_entry("Pace",
                      "wall clock",
                      Patterns::Selection("wall clock|as fast as possible"),
                      "How fast the run goes while the view is on: 'wall "
                      "clock' waits so that simulated time passes no faster "
                      "than real time (a run slower than real time is not "
                      "slowed further); 'as fast as possible' never waits. "
                      "The page can switch.");
    prm.declare_entry("Start paused",
                      "false",
                      Patterns::Bool(),
                      "Whether the run waits after its initial state until "
                      "a page presses play or step (only while a page is "
                      "open: with 'Wait for page', until one connects).");
    prm.declare_entry("Wait for page",
                      "0",
                      Patterns::Double(0, 3600),
                      "Seconds to wait for a page to connect before the "
                      "first step (0: start at once).");
    prm.declare_entry("Web directory",
                      "",
                      Patterns::Anything(),
                      "Where the page's files (index.html, view.js, "
                      "view.css) are; empty (default): web/ of the sources "
                      "this program was built from.");
    prm.declare_entry("three.js directory",
                      "/usr/share/javascript/three",
                      Patterns::Anything(),
                      "Where three.js is installed (Debian's libjs-three): "
                      "build/three.min.js and "
                      "examples/js/controls/OrbitControls.js are served from "
                      "there.");
    prm.leave_subsection();
    prm.leave_subsection();
  }


  template <int dim>
  LiveView<dim>::LiveView(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.enter_subsection("Live view");
    port                   = prm.get_integer("Port");
    address                = prm.get("Address");
    frame_rate             = prm.get_double("Frame rate");
    pace_wall              = prm.get("Pace") == "wall clock";
    paused                 = prm.get_bool("Start paused");
    wait_for_page          = prm.get_double("Wait for page");
    settings.web_directory = prm.get("Web directory");
    if (settings.web_directory.empty())
      settings.web_directory = TISSUEFEM_WEB_DIRECTORY;
    settings.three_directory = prm.get("three.js directory");
    prm.leave_subsection();
    prm.leave_subsection();
    // The run's own reading (the integrator's canonical name, as in the
    // run's first line).
    time::TimeParameters time_parameters;
    time_parameters.parse_parameters(prm);
    integrator = time_parameters.integrator;
    time_step  = time_parameters.time_step;
    budget     = time_parameters.real_time_budget;
    prm.enter_subsection("Materials");
    models = prm.get("Model");
    prm.leave_subsection();
    mouse_unavailable = tool::MouseGrasp<dim>::unavailable(prm);
  }


  template <int dim>
  LiveView<dim>::~LiveView() = default;


  template <int dim>
  void
  LiveView<dim>::initialize(const Context<dim> &c)
  {
    Interface<dim>::initialize(c);
    if (port < 0)
      return;
    require(dim >= 2,
            "Output/Live view/Port",
            "the live view shows a surface; a 1D body has none (set -1)");
    // Process 0 sends the whole body's surface (output::BoundarySurface).
    geometry::require_whole_mesh<dim>(c.scene.triangulation,
                                      "Output/Live view/Port",
                                      "the live view (set -1)");
    field_names = {"displacement", "J", "von Mises"};
    if (c.scene.obstacle_contact)
      field_names.push_back("contact pressure");
    if (const auto tool = c.scene.tools.find("contact");
        tool != c.scene.tools.end())
      contact_tool = dynamic_cast<tool::ContactTool<dim> *>(tool->second.get());
    obstacles = std::make_unique<output::ObstacleView<dim>>(
      c.scene.obstacle_contact.get(), contact_tool);
    // A new mesh needs a new surface; the next frame sends it.
    mesh_changed = c.scene.triangulation.signals.any_change.connect(
      [this]() { topology_sent = false; });
  }


  template <int dim>
  void
  LiveView<dim>::open()
  {
    if (port < 0)
      return;
    settings.address    = address;
    settings.port       = port;
    settings.frame_rate = frame_rate;
    if (parallel_tools::is_root())
      {
        server = std::make_unique<output::ViewServer>(settings);
        server->set_greeting(greeting());
        const std::string url
          = "http://" + address + ":" + std::to_string(server->port()) + "/";
        output::write_whole(this->context->directory + "/live_view",
                            [&](std::ostream &out) { out << url << '\n'; });
        auto &screen = parallel_tools::screen();
        screen << "live view: " << url << " (open it in a browser)"
               << std::endl;
        if (address != "127.0.0.1" && address != "::1")
          screen << "live view: WARNING: served on " << address
                 << ", not only to this machine: anyone who reaches it can "
                    "see and drive this run"
                 << std::endl;
      }
    run_start = pace_wall_origin = Clock::now();
  }


  template <int dim>
  void
  LiveView<dim>::restore(const std::vector<std::string> &)
  {
    open();
  }


  template <int dim>
  std::string
  LiveView<dim>::greeting() const
  {
    std::string fields;
    for (const auto &name : field_names)
      fields += (fields.empty() ? "" : ",") + output::json_quote(name);
    return std::string("{\"type\":\"scene\",\"dimension\":")
           + std::to_string(dim)
           + ",\"file\":" + output::json_quote(this->context->parameter_file)
           + ",\"description\":"
           + output::json_quote(this->context->scene.describe())
           + ",\"integrator\":" + output::json_quote(integrator)
           + ",\"materials\":" + output::json_quote(models) + ",\"directory\":"
           + output::json_quote(this->context->directory) + ",\"time_step\":"
           + json_number(time_step) + ",\"budget\":" + json_number(budget)
           + ",\"fields\":[" + fields + "],\"field\":" + std::to_string(field)
           + ",\"frame_rate\":" + json_number(frame_rate) + ",\"mouse\":"
           + (mouse_unavailable.empty() ? std::string("\"grasp\"")
                                        : output::json_quote(mouse_unavailable))
           + ",\"obstacles\":" + obstacles->json() + "}";
  }


  template <int dim>
  void
  LiveView<dim>::execute(const Step<dim> &step)
  {
    if (port < 0)
      return;
    const auto start = Clock::now();
    // Root decides; every process follows: [send a frame, field].
    std::vector<int> decision(2, 0);
    if (parallel_tools::is_root())
      {
        if (step.number == 0 && wait_for_page > 0)
          for (const auto until
               = Clock::now() + std::chrono::duration<double>(wait_for_page);
               server->pages() == 0 && Clock::now() < until;)
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        apply_commands(step.state.time);
        const bool due = seconds_since(last_frame) >= 1 / frame_rate;
        decision       = {(step.number == 0 || !topology_sent || paused
                     || (server->pages() > 0 && due))
                            ? 1
                            : 0,
                    int(field)};
        print_log();
      }
    decision
      = Utilities::MPI::broadcast(parallel_tools::communicator(), decision);
    field = decision[1];
    if (!topology_sent)
      send_topology();
    if (decision[0])
      send_frame(step, seconds_since(start));
  }


  template <int dim>
  void
  LiveView<dim>::wait(const time::State &state)
  {
    if (port < 0)
      return;
    if (server)
      hold(state.time);
    // A reset asked on process 0 ends the run here on every process; the
    // next run serves the same port, where the pages reconnect.
    const int again
      = Utilities::MPI::broadcast(parallel_tools::communicator(),
                                  reset_due ? int(server->port()) : -1);
    if (again < 0)
      return;
    if (server)
      close_with("{\"type\":\"reset\"}");
    throw ResetRequest{{"Output/Live view/Port=" + std::to_string(again),
                        "Output/Live view/Wait for page="
                          + std::to_string(std::max(wait_for_page, 10.))}};
  }


  template <int dim>
  void
  LiveView<dim>::apply_commands(const double time)
  {
    for (const auto &command : server->take_commands())
      {
        std::istringstream words(command.text);
        std::string        verb, argument;
        words >> verb;
        std::getline(words >> std::ws, argument);
        std::string refusal;
        if (verb == "pause")
          paused = true;
        else if (verb == "play" || verb == "step")
          {
            paused    = false;
            step_once = verb == "step";
          }
        else if (verb == "reset")
          refusal = reset_refusal();
        else if (verb == "pace" && (argument == "wall" || argument == "fast"))
          pace_wall = argument == "wall";
        else if (verb == "grasp" || verb == "drag" || verb == "release"
                 || verb == "tool")
          refusal = mouse_command(verb, argument);
        else if (verb == "field")
          {
            const auto f
              = std::find(field_names.begin(), field_names.end(), argument);
            if (f == field_names.end())
              refusal = "no field '" + output::printable(argument, 40) + "'";
            else
              field = f - field_names.begin();
          }
        else
          refusal
            = "unknown command '" + output::printable(command.text, 40) + "'";
        if (!refusal.empty())
          server->send_to(command.page,
                          "{\"type\":\"error\",\"message\":"
                            + output::json_quote(refusal) + "}");
        restart_pacing(time);
      }
  }


  template <int dim>
  std::string
  LiveView<dim>::reset_refusal()
  {
    // A device's positions carry its own clock, which cannot go back.
    for (const auto &[name, tool] : this->context->scene.tools)
      if (tool->follows_device())
        return "the run cannot start again: a device drives the " + name
               + " tool";
    reset_due = true;
    return {};
  }


  template <int dim>
  void
  LiveView<dim>::restart_pacing(const double time)
  {
    pace_wall_origin = Clock::now();
    pace_time_origin = time;
  }


  template <int dim>
  tool::MouseGrasp<dim> *
  LiveView<dim>::mouse() const
  {
    const auto &tools = this->context->scene.tools;
    const auto  found = tools.find("mouse");
    return found == tools.end()
             ? nullptr
             : dynamic_cast<tool::MouseGrasp<dim> *>(found->second.get());
  }


  template <int dim>
  std::string
  LiveView<dim>::mouse_command(const std::string &verb,
                               const std::string &argument)
  {
    // Three numbers (the page's z is 0 in 2D), but for 'release'.
    std::istringstream numbers(argument);
    double             x[3];
    if (verb != "release" && !(numbers >> x[0] >> x[1] >> x[2]))
      return verb + " needs three numbers";
    if (verb == "tool")
      {
        if (!contact_tool)
          return "the scene has no contact tool";
        Tensor<1, dim> offset;
        for (unsigned int d = 0; d < dim; ++d)
          offset[d] = x[d];
        return contact_tool->request_move(offset);
      }
    tool::MouseGrasp<dim> *mouse = this->mouse();
    if (!mouse)
      return "the mouse cannot grasp in this run: " + mouse_unavailable;
    if (verb == "release")
      {
        mouse->request_release();
        return {};
      }
    if (verb == "grasp")
      {
        Point<dim> point;
        for (unsigned int d = 0; d < dim; ++d)
          point[d] = x[d];
        return mouse->request_grasp(point);
      }
    Tensor<1, dim> drag;
    for (unsigned int d = 0; d < dim; ++d)
      drag[d] = x[d];
    return mouse->request_drag(drag);
  }


  template <int dim>
  void
  LiveView<dim>::send_topology()
  {
    surface = std::make_unique<output::BoundarySurface<dim>>(
      this->context->scene.triangulation);
    topology_sent = true;
    if (!parallel_tools::is_root())
      return;
    auto bytes = std::make_shared<std::string>("TFT1");
    put<std::uint32_t>(*bytes, surface->vertices.size());
    put<std::uint32_t>(*bytes, surface->triangles.size() / 3);
    put<std::uint32_t>(*bytes, dim);
    put_all(*bytes, surface->positions);
    put_all(*bytes, surface->triangles);
    // The obstacles' drawings; unbounded ones cut to three diameters.
    const auto box
      = GridTools::compute_bounding_box(this->context->scene.triangulation);
    obstacles->append_drawings(*bytes,
                               box.center(),
                               3
                                 * box.get_boundary_points().first.distance(
                                   box.get_boundary_points().second));
    server->set_topology(std::move(bytes));
  }


  template <int dim>
  void
  LiveView<dim>::send_frame(const Step<dim> &step, const double waited)
  {
    const auto  start = Clock::now();
    const auto &scene = this->context->scene;
    // Not const: the energies below keep what they computed.
    auto                      &solid = *scene.solid;
    std::vector<Vector<float>> cells;
    const std::string         &name = field_names[field];
    if (name == "J" || name == "von Mises")
      {
        Vector<float> jacobian, von_mises;
        solid::cell_fields(*scene.discretization,
                           solid.get_materials(),
                           solid.fibres(),
                           solid.deformation(step.u_ghosted).get(),
                           step.u_ghosted,
                           jacobian,
                           von_mises);
        cells.push_back(name == "J" ? jacobian : von_mises);
      }
    else if (name == "contact pressure")
      {
        Vector<float> pressure, gap;
        scene.obstacle_contact->cell_fields(step.u_ghosted,
                                            step.state.time,
                                            pressure,
                                            gap);
        cells.push_back(pressure);
      }
    // Collective; the statistics reuse the stored energy (Solid caches
    // the last state's).
    const double       stored  = solid.stored_energy(step.state.u);
    const double       kinetic = solid.kinetic_energy(step.state.v);
    std::vector<float> displacement;
    std::vector<std::vector<float>> values;
    surface->gather(scene.discretization->dof_handler,
                    step.u_ghosted,
                    cells,
                    displacement,
                    values);
    if (!parallel_tools::is_root())
      return;
    const double frame_ms = 1e3 * (seconds_since(start) + waited);
    auto         bytes    = std::make_shared<std::string>("TFF1");
    put<std::uint32_t>(*bytes, step.number);
    put<std::uint32_t>(*bytes, surface->vertices.size());
    put<std::uint32_t>(*bytes, field);
    put<std::uint32_t>(*bytes, (paused ? 1 : 0) | (pace_wall ? 2 : 0));
    // Simulated seconds per wall-clock second over the last second or so.
    const double wall = seconds_since(run_start);
    recent.emplace_back(wall, step.state.time);
    while (recent.size() > 2 && wall - recent[1].first > 1)
      recent.pop_front();
    const double rate = wall > recent.front().first
                          ? (step.state.time - recent.front().second)
                              / (wall - recent.front().first)
                          : 0.;
    // A live device's answer latency (ms; -1 without one).
    std::vector<double> latency = {-1., -1.};
    for (const auto &[tool_name, tool] : scene.tools)
      if (const auto l = tool->haptic_latency(); l.size() == 2)
        latency = l;
    for (const double x : {step.state.time,
                           step.report.dt,
                           step.report.step_seconds,
                           stored,
                           kinetic,
                           rate,
                           frame_ms,
                           budget,
                           latency[0],
                           latency[1]})
      put<double>(*bytes, std::isfinite(x) ? x : 0.);
    put_all(*bytes, displacement);
    if (!values.empty())
      put_all(*bytes, values[0]);
    // The grasp (the mouse's, or the scene's grasping tool's): holding (0
    // or 1), the grasp point (reference), the displacement it imposes, the
    // force on it after the previous step.
    std::vector<float> grasp_block(10, 0.f);
    for (const auto &[name, tool] : scene.tools)
      if (const auto grasp = tool->grasp(step.state.time))
        {
          grasp_block[0] = 1;
          for (unsigned int d = 0; d < dim; ++d)
            {
              grasp_block[1 + d] = grasp->point[d];
              grasp_block[4 + d] = grasp->displacement[d];
              grasp_block[7 + d] = grasp->force[d];
            }
        }
    put_all(*bytes, grasp_block);
    obstacles->append_poses(*bytes, step.contact, step.state.time);
    server->set_frame(std::move(bytes));
    last_frame = Clock::now();
    ++frames;
  }


  template <int dim>
  void
  LiveView<dim>::hold(const double time)
  {
    // A signal ends the pause: the run then stops after this step as usual.
    while (paused && !reset_due && server->pages() > 0
           && !interruption_received_here())
      {
        server->wait(0.1);
        apply_commands(time);
        print_log();
      }
    if (reset_due)
      return;
    if (step_once)
      {
        // The next step runs, then the run pauses again.
        step_once = false;
        paused    = server->pages() > 0;
        restart_pacing(time);
        return;
      }
    paused = false;
    if (!pace_wall)
      return;
    const double ahead
      = (time - pace_time_origin) - seconds_since(pace_wall_origin);
    if (ahead > 0)
      std::this_thread::sleep_for(std::chrono::duration<double>(ahead));
  }


  template <int dim>
  void
  LiveView<dim>::print_log()
  {
    for (const auto &line : server->take_log())
      parallel_tools::screen() << line << std::endl;
  }


  template <int dim>
  void
  LiveView<dim>::finish(const time::State &state,
                        const RunTotals &,
                        output::RunRecord &)
  {
    if (!server)
      return;
    print_log();
    parallel_tools::screen()
      << "live view: " << frames << " frames sent" << std::endl;
    close_with("{\"type\":\"end\",\"time\":" + json_number(state.time)
               + ",\"frames\":" + std::to_string(frames) + "}");
  }

  template <int dim>
  void
  LiveView<dim>::abort(const std::string &what)
  {
    if (!server)
      return;
    close_with("{\"type\":\"error\",\"fatal\":true,\"message\":"
               + output::json_quote(what) + "}");
  }


  template <int dim>
  void
  LiveView<dim>::close_with(const std::string &last_message)
  {
    server->finish(last_message);
    server->close();
    print_log();
    server.reset();
  }


  template class LiveView<1>;
  template class LiveView<2>;
  template class LiveView<3>;

  TISSUEFEM_REGISTER_POSTPROCESSOR(
    LiveView,
    "live view",
    "a web page showing the run as it goes ('Output/Live view')");
} // namespace tissuefem::postprocess
