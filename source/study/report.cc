#include <deal.II/base/convergence_table.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/study/report.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace tissuefem::study
{
  double
  Row::cost() const
  {
    const double t = get("simulated time");
    return t > 0 ? get("wall steps") / t : get("wall steps");
  }


  std::vector<unsigned int>
  pareto_front(const std::vector<Row> &rows)
  {
    std::vector<unsigned int> front;
    for (unsigned int i = 0; i < rows.size(); ++i)
      {
        if (!rows[i].finished)
          continue;
        bool dominated = false;
        for (unsigned int j = 0; j < rows.size() && !dominated; ++j)
          dominated
            = j != i && rows[j].finished && rows[j].error <= rows[i].error
              && rows[j].get("wall total") <= rows[i].get("wall total")
              && (rows[j].error < rows[i].error
                  || rows[j].get("wall total") < rows[i].get("wall total"));
        if (!dominated)
          front.push_back(i);
      }
    std::sort(front.begin(), front.end(), [&](unsigned int a, unsigned int b) {
      return rows[a].get("wall total") < rows[b].get("wall total");
    });
    return front;
  }


  void
  write_csv(const std::string       &file,
            const std::vector<Axis> &axes,
            const std::vector<Row>  &rows,
            const std::string       &quantity)
  {
    const std::string temporary = file + ".new";
    std::ofstream     out(temporary);
    require(static_cast<bool>(out), "Study/Directory", "cannot write " + file);
    out << std::setprecision(10);
    out << "variant";
    for (const Axis &a : axes)
      out << ",\"" << a.name << "\"";
    out << ",status,cells,unknowns,processes,threads,steps,mean time step "
           "(time units),wall total (s),wall steps (s),wall assembly (s),wall "
           "solve (s),step median (s),step p95 (s),wall per time unit (s),"
           "peak memory (MB),process wall (s),\"error: "
        << quantity
        << "\",error estimate (stress jump; H1 seminorm units),effectivity "
           "(estimate / H1 error)\n";
    for (const Row &r : rows)
      {
        out << r.variant.index;
        for (const auto &l : r.variant.axis_labels)
          out << ",\"" << l << "\"";
        out << ',' << r.status;
        if (r.finished)
          {
            for (const char *key :
                 {"cells", "unknowns", "processes", "threads", "steps"})
              out << ',' << r.get(key);
            out << ',' << r.mean_step();
            for (const char *key : {"wall total",
                                    "wall steps",
                                    "wall assembly",
                                    "wall solve",
                                    "step median",
                                    "step p95"})
              out << ',' << r.get(key);
            out << ',' << r.cost() << ',' << r.get("peak memory") << ','
                << r.wall_seconds << ',' << r.error;
            // Only runs of a manufactured solution know their true error.
            for (const char *key : {"error estimate", "effectivity"})
              if (r.record.count(key))
                out << ',' << r.get(key);
              else
                out << ',';
            out << '\n';
          }
        else
          out << ",,,,,,,,,,,,,,," << r.wall_seconds << ",,,\n";
      }
    out.close();
    require(static_cast<bool>(out), "Study/Directory", "cannot write " + file);
    std::rename(temporary.c_str(), file.c_str());
  }


  namespace
  {
    /// The series a row belongs to: its labels on every axis but the rate
    /// axis.
    std::string
    series_name(const Row &row, const unsigned int rate_axis)
    {
      std::string name;
      for (unsigned int a = 0; a < row.variant.axis_pieces.size(); ++a)
        if (a != rate_axis)
          name += (name.empty() ? "" : ", ") + row.variant.axis_pieces[a];
      return name.empty() ? "all variants" : name;
    }


    /// Series names in order of first appearance, with their row indices.
    std::vector<std::pair<std::string, std::vector<unsigned int>>>
    series_of(const std::vector<Row> &rows, const unsigned int rate_axis)
    {
      std::vector<std::pair<std::string, std::vector<unsigned int>>> series;
      for (unsigned int i = 0; i < rows.size(); ++i)
        {
          const std::string name = series_name(rows[i], rate_axis);
          auto              it
            = std::find_if(series.begin(), series.end(), [&](const auto &s) {
                return s.first == name;
              });
          if (it == series.end())
            series.push_back({name, {i}});
          else
            it->second.push_back(i);
        }
      return series;
    }


    std::string
    quoted(std::string s)
    {
      std::replace(s.begin(), s.end(), '"', '\'');
      return "\"" + s + "\"";
    }
  } // namespace


  void
  write_convergence_tables(std::ostream            &out,
                           const std::string       &directory,
                           const std::vector<Axis> &axes,
                           const std::vector<Row>  &rows,
                           const unsigned int       rate_axis,
                           const std::string       &rates_against,
                           const unsigned int       dim)
  {
    std::ofstream rates(directory + "/rates.csv");
    rates << "series,from variant,to variant,observed order (" << rates_against
          << ")\n"
          << std::setprecision(6);
    for (const auto &[name, indices] : series_of(rows, rate_axis))
      {
        ConvergenceTable table;
        const Row       *previous = nullptr;
        unsigned int     n_rows   = 0;
        for (const unsigned int i : indices)
          {
            const Row &r = rows[i];
            if (!r.finished)
              continue;
            ++n_rows;
            table.add_value(axes.empty() ? "variant" : axes[rate_axis].name,
                            r.variant.axis_labels.empty()
                              ? std::to_string(r.variant.index)
                              : r.variant.axis_labels[rate_axis]);
            table.add_value("cells", static_cast<unsigned int>(r.get("cells")));
            table.add_value("unknowns",
                            static_cast<unsigned int>(r.get("unknowns")));
            const double dt = r.mean_step();
            table.add_value("mean dt", dt);
            table.add_value("1/dt", 1. / dt);
            table.add_value("error", r.error);
            table.add_value("wall (s)", r.get("wall total"));
            if (previous)
              {
                const double order
                  = rates_against == "time step"
                      ? std::log(previous->error / r.error)
                          / std::log(previous->mean_step() / dt)
                      : dim * std::log(previous->error / r.error)
                          / std::log(r.get("unknowns")
                                     / previous->get("unknowns"));
                rates << quoted(name) << ',' << previous->variant.index << ','
                      << r.variant.index << ',' << order << '\n';
              }
            previous = &r;
          }
        if (n_rows == 0)
          continue;
        table.set_scientific("error", true);
        table.set_scientific("mean dt", true);
        table.set_precision("error", 3);
        table.set_precision("wall (s)", 3);
        table.set_precision("mean dt", 3);
        if (rates_against == "time step")
          table.evaluate_convergence_rates(
            "error", "1/dt", ConvergenceTable::reduction_rate_log2, 1);
        else if (rates_against == "unknowns")
          table.evaluate_convergence_rates(
            "error", "unknowns", ConvergenceTable::reduction_rate_log2, dim);
        table.omit_column_from_convergence_rate_evaluation("wall (s)");
        out << "series: " << name << '\n';
        table.write_text(out, TableHandler::org_mode_table);
        out << '\n';
      }
  }


  std::string
  draw_charts(const std::string &directory,
              const std::string &title,
              const std::vector<Axis> &,
              const std::vector<Row> &rows,
              const unsigned int      rate_axis,
              const std::string      &quantity)
  {
    const auto    series = series_of(rows, rate_axis);
    std::ofstream gp(directory + "/charts.gp");
    gp << "# Drawn by tissuefem's study: gnuplot charts.gp (in this "
          "directory)\n"
       << "set terminal pngcairo size 1000,650 font ',10'\n"
       << "set logscale xy\nset grid\nset key below\n"
       << "set format y '%.0e'\n"
       << "set title " << quoted(title) << " noenhanced\n"
       << "set ylabel " << quoted(quantity) << " noenhanced\n";
    std::string unknowns_plot, wall_plot;
    for (unsigned int s = 0; s < series.size(); ++s)
      {
        const std::string file = "series-" + std::to_string(s + 1) + ".dat";
        std::ofstream     data(directory + "/" + file);
        data << "# unknowns, wall total (s), error, variant\n"
             << std::setprecision(10);
        unsigned int n = 0;
        for (const unsigned int i : series[s].second)
          if (rows[i].finished && rows[i].error > 0)
            {
              data << rows[i].get("unknowns") << ' '
                   << rows[i].get("wall total") << ' ' << rows[i].error << ' '
                   << quoted(std::to_string(rows[i].variant.index)) << '\n';
              ++n;
            }
        if (n == 0)
          continue;
        const std::string sep = unknowns_plot.empty() ? "" : ", \\\n  ";
        // One line per series, the same point type and colour in both.
        const auto line = [&](const std::string &columns) {
          return sep + quoted(file) + " using " + columns
                 + " with linespoints lw 2 pt " + std::to_string(s % 13 + 1)
                 + " lc " + std::to_string(s + 1) + " title "
                 + quoted(series[s].first);
        };
        unknowns_plot += line("1:3");
        wall_plot += line("2:3");
      }
    if (unknowns_plot.empty())
      return "no charts: no variant finished with a positive error";
    {
      std::ofstream front(directory + "/front.dat");
      front << "# wall total (s), error, variant: the Pareto front\n"
            << std::setprecision(10);
      for (const unsigned int i : pareto_front(rows))
        front << rows[i].get("wall total") << ' ' << rows[i].error << ' '
              << quoted(std::to_string(rows[i].variant.index)) << '\n';
    }
    gp << "set output 'error_vs_unknowns.png'\n"
       << "set xlabel 'unknowns (displacement degrees of freedom)'\n"
       << "plot " << unknowns_plot << "\n"
       << "set output 'error_vs_wall_time.png'\n"
       << "set xlabel 'wall time of the run (s)'\n"
       << "plot " << wall_plot
       << ", \\\n  'front.dat' using 1:2 with steps lw 3 lc rgb 'black' "
          "title 'Pareto front (numbers: variants in results.csv)', \\\n"
          "  'front.dat' using 1:2:3 with labels offset 0.8,0.8 "
          "font ',9' notitle\n";
    gp.close();
    if (std::system("command -v gnuplot > /dev/null 2>&1") != 0)
      return "gnuplot is not installed: the charts' script and data are in "
             + directory + " (charts.gp)";
    const std::string command
      = "cd '" + directory + "' && gnuplot charts.gp > gnuplot.log 2>&1";
    if (std::system(command.c_str()) != 0)
      return "gnuplot failed (see " + directory + "/gnuplot.log)";
    return "charts: " + directory + "/error_vs_unknowns.png and " + directory
           + "/error_vs_wall_time.png";
  }


  std::string
  summary_paragraph(const std::vector<Row>    &rows,
                    const std::vector<double> &tolerances,
                    const std::string         &quantity)
  {
    std::ostringstream s;
    s << std::setprecision(3);
    const auto describe = [&](const Row &r) {
      std::ostringstream d;
      d << std::setprecision(3) << "#" << r.variant.index << " ("
        << r.variant.label << "; error " << r.error << ", "
        << r.get("wall total") << " s)";
      return d.str();
    };
    const auto front = pareto_front(rows);
    s << "On the Pareto front of " << quantity
      << " against wall time (no other variant is both more accurate and "
         "faster), from fastest to most accurate: ";
    for (unsigned int k = 0; k < front.size(); ++k)
      s << (k ? "; " : "") << describe(rows[front[k]]);
    s << '.';
    for (const double tol : tolerances)
      {
        const Row *best = nullptr;
        for (const Row &r : rows)
          if (r.finished && r.error <= tol
              && (!best || r.get("wall total") < best->get("wall total")))
            best = &r;
        s << " For errors up to " << tol << ", the fastest is "
          << (best ? describe(*best)
                   : std::string("none (no variant is that accurate)"))
          << '.';
      }
    unsigned int failed = 0;
    for (const Row &r : rows)
      failed += !r.finished;
    if (failed > 0)
      {
        s << ' ' << failed << " variant(s) did not finish:";
        for (const Row &r : rows)
          if (!r.finished)
            s << " #" << r.variant.index << " (" << r.variant.label << ": "
              << r.status << ")";
        s << '.';
      }
    return s.str();
  }
} // namespace tissuefem::study
