// Tools are plugins (tool/interface.h): a kind registered outside the
// library (here a 'marker' that reports a force it makes up) is created by
// the scene when its subsection asks for it, next to the grasping tool, and
// the 'tool force' postprocessor writes one pair of files per tool:
// tool_force-NAME.csv and haptic_force-NAME.csv, with summary lines
// 'tool force (NAME)'; a single tool keeps the plain names.
// Expected values: the marker's rows are what it reports, t -> (t, 2 t);
// the grasping tool pulls a 1D bar (E = 1, L = 1) clamped at x = 0 by
// d(t) = 0.1 t until t = 0.5, so the tissue pulls back with -0.1 t, then 0
// (as tests/prm/tool_pull_bar_1d, a closed form).

#include <deal.II/base/mpi.h>

#include <tissuefem/app/parameters.h>
#include <tissuefem/tool/interface.h>

#include "../run_program.h"
#include "../tests.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

using namespace dealii;
using namespace tissuefem;

namespace
{
  /// A tool that never touches the tissue and reports position t and force
  /// 2 t (and one haptic sample per step, exact).
  template <int dim>
  class Marker : public tool::Interface<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Marker");
      prm.declare_entry("Enabled", "false", Patterns::Bool(), "Test tool.");
      prm.leave_subsection();
    }

    static std::unique_ptr<tool::Interface<dim>>
    create(ParameterHandler &prm, const Triangulation<dim> &)
    {
      prm.enter_subsection("Marker");
      const bool enabled = prm.get_bool("Enabled");
      prm.leave_subsection();
      return enabled ? std::make_unique<Marker<dim>>() : nullptr;
    }

    bool
    due(const double) const override
    {
      return false;
    }

    void
    act(const time::State &, solid::Solid<dim> &) override
    {
    }

    tool::Record<dim>
    record(const time::State &state,
           solid::Solid<dim> &,
           const contact::Reports<dim> &) override
    {
      tool::Record<dim> r;
      r.position[0] = state.time;
      r.force[0]    = 2 * state.time;
      r.engaged     = true;
      r.haptic.push_back({state.time, r.force, 0.});
      ++records;
      return r;
    }

    std::string
    summary() const override
    {
      return "marker: " + std::to_string(records) + " records";
    }

  private:
    unsigned int records = 0;
  };

  template class Marker<1>;
  template class Marker<2>;
  template class Marker<3>;

  TISSUEFEM_REGISTER_TOOL(Marker, "marker", "a test tool.")

  const char *scene = R"(set Dimension = 1
subsection Geometry
  set Lower corner = 0
  set Upper corner = 1
  set Subdivisions = 4
end
subsection Materials
  set Model           = linear elastic
  set Young's modulus = 1
  set Poisson's ratio = 0
end
subsection Boundary conditions
  set Dirichlet = 0: x: 0
end
subsection Tool
  set Grasp point  = 1
  set Grasp radius = 0.01
  set Trajectory   = 0.1*t
  set Release time = 0.5
end
subsection Time integration
  set Integrator = quasistatic
  set End time   = 1
  set Time step  = 0.25
end
subsection Output
  set Directory    = results
  set Summary file = summary.txt
  subsection VTU
    set Interval = 0
  end
end
)";

  /// Runs the scene (with the marker if @p marker), screen output muted;
  /// returns the exit status.
  int
  run(const bool marker)
  {
    std::filesystem::remove_all("results");
    {
      std::ofstream file("scene.prm");
      file << scene << "subsection Marker\n  set Enabled = "
           << (marker ? "true" : "false") << "\nend\n";
    }
    const int status = tissuefem_tests::run_program({"scene.prm"});
    return status;
  }

  /// The rows of a CSV file after its header, as numbers.
  std::vector<std::vector<double>>
  rows(const std::string &path)
  {
    std::vector<std::vector<double>> result;
    std::ifstream                    in(path);
    std::string                      line;
    std::getline(in, line);
    while (std::getline(in, line))
      {
        std::vector<double> row;
        std::istringstream  fields(line);
        for (std::string f; std::getline(fields, f, ',');)
          row.push_back(std::stod(f));
        result.push_back(row);
      }
    return result;
  }

  /// Whether @p path holds the rows (t, 1, x(t), f(t)) for t = 0, 0.25,
  /// ..., 1 to 1e-12 (the 'holding' column is not checked).
  template <typename X, typename F>
  bool
  force_rows(const std::string &path, const X &x, const F &f)
  {
    const auto r = rows(path);
    if (r.size() != 5)
      return false;
    for (unsigned int i = 0; i < 5; ++i)
      {
        const double t = 0.25 * i;
        if (r[i].size() != 4 || std::abs(r[i][0] - t) > 1e-12
            || std::abs(r[i][2] - x(t)) > 1e-12
            || std::abs(r[i][3] - f(t)) > 1e-12)
          return false;
      }
    return true;
  }

  bool
  contains(const std::string &path, const std::string &text)
  {
    std::ifstream     in(path);
    std::stringstream all;
    all << in.rdbuf();
    return all.str().find(text) != std::string::npos;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const auto grasp_x = [](const double t) { return 0.1 * t; };
  const auto grasp_f = [](const double t) { return t <= 0.5 ? -0.1 * t : 0.; };

  tissuefem_tests::check(run(true) == 0, "two tools: the run succeeds");
  tissuefem_tests::check(force_rows("results/tool_force-grasp.csv",
                                    grasp_x,
                                    grasp_f),
                         "two tools: tool_force-grasp.csv is the closed form");
  tissuefem_tests::check(
    force_rows(
      "results/tool_force-marker.csv",
      [](const double t) { return t; },
      [](const double t) { return 2 * t; }),
    "two tools: tool_force-marker.csv is what the marker reported");
  tissuefem_tests::check(
    rows("results/haptic_force-marker.csv").size() == 5
      && std::filesystem::exists("results/haptic_force-grasp.csv")
      && !std::filesystem::exists("results/tool_force.csv"),
    "two tools: one pair of files each, named");
  tissuefem_tests::check(
    contains("summary.txt", "t = 0.25 tool force (grasp) = -0.025")
      && contains("summary.txt", "t = 0.25 tool force (marker) = 0.5"),
    "two tools: summary lines name the tool");

  tissuefem_tests::check(
    run(false) == 0 && force_rows("results/tool_force.csv", grasp_x, grasp_f)
      && !std::filesystem::exists("results/tool_force-grasp.csv")
      && contains("summary.txt", "t = 0.25 tool force = -0.025"),
    "one tool: the plain names");
  return tissuefem_tests::exit_status();
}
