#include <deal.II/base/multithread_info.h>

#include <tissuefem/postprocess/run_record.h>

#include <algorithm>
#include <numeric>

namespace tissuefem::postprocess
{
  template <int dim>
  void
  RunRecordRows<dim>::finish(const time::State &state,
                             const RunTotals   &totals,
                             output::RunRecord &r)
  {
    std::vector<double> seconds = totals.step_seconds;
    const double        steps_wall
      = std::accumulate(seconds.begin(), seconds.end(), 0.);
    std::sort(seconds.begin(), seconds.end());
    const auto percentile = [&](const double p) {
      return seconds.empty()
               ? 0.
               : seconds[std::min<std::size_t>(seconds.size() - 1,
                                               static_cast<std::size_t>(
                                                 p * seconds.size()))];
    };
    const auto &scene = this->context->scene;
    r.add("processes", parallel_tools::n_processes(), "MPI processes");
    r.add("threads", MultithreadInfo::n_threads(), "threads per process");
    r.add("cells",
          scene.triangulation.n_global_active_cells(),
          "active cells at the end");
    r.add("unknowns",
          scene.solid->n_dofs(),
          "displacement unknowns at the end");
    r.add("steps", seconds.size(), "steps reported (rows of statistics.csv)");
    r.add("simulated time", state.time, "time units reached");
    r.add("newton iterations", totals.newton_iterations, "sum over steps");
    r.add("rejected attempts", totals.rejected_attempts, "sum over steps");
    r.add("wall total", totals.wall_seconds, "s, set-up, steps and output");
    r.add("wall steps", steps_wall, "s, sum of the integrator's steps");
    r.add("wall assembly",
          totals.assembly_seconds,
          "s, residual and Jacobian assembly in the steps");
    r.add("wall solve", totals.solve_seconds, "s, linear solves in the steps");
    r.add("step median", percentile(0.5), "s wall per step, median");
    r.add("step p95", percentile(0.95), "s wall per step, 95th percentile");
    r.add("step max", percentile(1.), "s wall per step, largest");
    r.add("peak memory",
          totals.peak_bytes / 1e6,
          "MB resident, sum over processes");
    r.add("peak memory per process",
          totals.peak_bytes_largest / 1e6,
          "MB resident, the largest process's");
    for (const auto &[part, bytes] : totals.memory_parts)
      r.add("memory " + part,
            bytes / 1e6,
            "MB held at the end by the solid's " + part
              + ", sum over processes");
  }

  template class RunRecordRows<1>;
  template class RunRecordRows<2>;
  template class RunRecordRows<3>;

  TISSUEFEM_REGISTER_POSTPROCESSOR(
    RunRecordRows,
    "run record",
    "run.txt: sizes, wall times and memory of the finished run (other "
    "postprocessors add their figures to it).")
} // namespace tissuefem::postprocess
