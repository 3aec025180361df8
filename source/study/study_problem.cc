#include <tissuefem/app/parameters.h>
#include <tissuefem/base/input_error.h>
#include <tissuefem/base/interruption.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/base/timing.h>
#include <tissuefem/output/run_record.h>
#include <tissuefem/study/runner.h>
#include <tissuefem/study/study_problem.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

namespace tissuefem::study
{
  void
  Study::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Study");
    prm.declare_entry("Scene",
                      "",
                      Patterns::FileName(),
                      "The elasticity scene (.prm) every variant runs, "
                      "relative to this file's directory.");
    prm.declare_entry("Settings",
                      "",
                      Patterns::Anything(),
                      "'Subsection/Name = value; ...' applied to every run "
                      "of the study (e.g. 'Output/VTU/Interval = 0').");
    prm.declare_entry(
      "Axes",
      "",
      Patterns::Anything(),
      "The variants: the Cartesian product of the axes, separated by '|'. "
      "An axis is 'Subsection/Name: v1; v2; ...' (values of one parameter) "
      "or 'name: label1 {Subsection/Name = v & Subsection/Name = v}; label2 "
      "{...}' (several settings per value). Later axes override earlier "
      "ones where they set the same parameter. Several such products, "
      "separated by '||' and with the same axis names, are run one after "
      "the other (e.g. each integrator with time steps that suit it).");
    prm.declare_entry("Rate axis",
                      "",
                      Patterns::Anything(),
                      "The axis whose values form one convergence series "
                      "(one line in each chart); variants that agree on "
                      "every other axis are one series. Empty: the first "
                      "axis.");
    prm.declare_entry("Rates against",
                      "unknowns",
                      Patterns::Selection("unknowns|time step|none"),
                      "Observed orders: of the error in h, estimated as "
                      "N^(-1/dim) from the unknowns N; or in the mean time "
                      "step (simulated time / steps); or none.");
    prm.declare_entry("Tolerances",
                      "",
                      Patterns::List(Patterns::Double(0)),
                      "Errors for which the summary names the fastest "
                      "variant that is that accurate.");
    prm.declare_entry("Directory",
                      "study",
                      Patterns::FileName(),
                      "Where results.csv, rates.csv, convergence.txt, the "
                      "charts, summary.txt and one directory per variant "
                      "go (relative to the working directory).");
    prm.declare_entry("Runs directory",
                      "",
                      Patterns::FileName(),
                      "Where the variants' runs go ('variant-K' each, "
                      "'reference'); empty: 'Directory'. A study of another "
                      "quantity over the same runs points here to the first "
                      "study's runs and reuses them.");
    prm.declare_entry("Launcher",
                      "",
                      Patterns::Anything(),
                      "Words put before each run's command, e.g. 'mpirun "
                      "-np 2' for runs on two MPI processes; the study "
                      "itself runs on one.");
    prm.declare_entry("Threads per variant",
                      "1",
                      Patterns::Integer(0, 1024),
                      "Threads per process of each run (0: all cores); one "
                      "by default so that the wall times of different "
                      "variants are comparable on a shared machine.");
    prm.declare_entry("Title",
                      "",
                      Patterns::Anything(),
                      "Title of the charts (empty: the scene's file name).");
    study::QuantityParameters::declare_parameters(prm);
    study::PickerParameters::declare_parameters(prm);
    prm.leave_subsection();
  }


  Study::Study(ParameterHandler &prm, const problems::RunContext &context)
      : context(context)
  {
    require(parallel_tools::n_processes() == 1,
            "Problem",
            "a study runs on one process; its variants can use MPI through "
            "'Study/Launcher'");
    // Until setup() reads the scene's own (orders in h need it).
    scene_dimension = prm.get_integer("Dimension");
    prm.enter_subsection("Study");
    scene = prm.get("Scene");
    require(!scene.empty(), "Study/Scene", "is empty");
    if (!scene.empty() && scene[0] != '/'
        && !context.parameter_directory.empty())
      scene = context.parameter_directory + "/" + scene;
    settings
      = study::parse_settings(prm.get("Settings"), ';', "Study/Settings");
    variants       = study::parse_variants(prm.get("Axes"), "Study/Axes", axes);
    rates_against  = prm.get("Rates against");
    directory      = prm.get("Directory");
    runs_directory = prm.get("Runs directory");
    launcher       = prm.get("Launcher");
    threads        = prm.get_integer("Threads per variant");
    title          = prm.get("Title");
    if (title.empty())
      title = std::filesystem::path(scene).filename().string();
    const std::string rate_name = prm.get("Rate axis");
    rate_axis                   = 0;
    if (!rate_name.empty())
      {
        rate_axis = axes.size();
        for (unsigned int a = 0; a < axes.size(); ++a)
          if (axes[a].name == rate_name)
            rate_axis = a;
        require(rate_axis < axes.size(),
                "Study/Rate axis",
                "'" + rate_name + "' is none of the axes' names");
      }
    for (const auto &t : split_and_trim(prm.get("Tolerances"), ','))
      if (!t.empty())
        tolerances.push_back(std::stod(t));
    quantity.parse_parameters(prm);
    picker.parse_parameters(prm);
    prm.leave_subsection();
    require(!axes.empty(), "Study/Axes", "is empty: a study needs variants");
    require(!directory.empty(), "Study/Directory", "is empty");
    if (runs_directory.empty())
      runs_directory = directory;
  }


  std::vector<std::string>
  Study::arguments(const std::vector<study::Setting> &extra,
                   const std::string                 &output) const
  {
    std::vector<std::string> args = {scene};
    for (const auto *list : {&settings, &extra})
      for (const auto &s : *list)
        {
          args.push_back("--set");
          args.push_back(s.assignment());
        }
    args.push_back("--set");
    args.push_back("Output/Directory=" + output);
    if (threads > 0)
      {
        args.push_back("--threads");
        args.push_back(std::to_string(threads));
      }
    return args;
  }


  study::Variant
  Study::reference_variant() const
  {
    study::Variant v;
    v.index    = 0;
    v.label    = "reference";
    v.settings = study::parse_settings(quantity.reference_settings,
                                       ';',
                                       "Study/Reference settings");
    return v;
  }


  void
  Study::setup()
  {
    // Every run's parameters must be valid before the first one starts: a
    // typo in the last variant must not cost the whole study.
    std::vector<study::Variant> all = variants;
    if (quantity.reference == "reference run")
      all.push_back(reference_variant());
    for (const auto &v : all)
      {
        ParameterHandler         prm;
        std::vector<std::string> overrides;
        for (const auto &s : settings)
          overrides.push_back(s.assignment());
        for (const auto &s : v.settings)
          overrides.push_back(s.assignment());
        try
          {
            declare_parameters_for(prm, scene, overrides);
            read_parameters(prm, scene, overrides);
          }
        catch (const InputError &e)
          {
            throw InputError("Study/Scene '" + scene + "' with variant '"
                             + v.label + "': " + e.what());
          }
        if (&v == &all.front())
          scene_dimension = prm.get_integer("Dimension");
        require(prm.get("Problem") == "elasticity",
                "Study/Scene",
                "'" + scene + "' is no elasticity scene");
        if (quantity.reference == "manufactured")
          {
            prm.enter_subsection("Manufactured solution");
            const bool enabled = prm.get_bool("Enabled");
            prm.leave_subsection();
            require(enabled,
                    "Study/Reference",
                    "'manufactured' needs 'Manufactured solution/Enabled = "
                    "true' in the scene (variant '"
                      + v.label + "')");
          }
      }
  }


  study::RunOutcome
  Study::launch(const std::vector<study::Setting> &extra,
                const std::string                 &output,
                const std::string                 &what) const
  {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::remove_all(output, ec);
    fs::create_directories(output, ec);
    require(!ec, "Study/Directory", "cannot create '" + output + "'");
    const study::RunOutcome outcome = study::run_child(study::own_executable(),
                                                       arguments(extra, output),
                                                       launcher,
                                                       output + "/log.txt");
    if (outcome.exit_status == 127)
      throw InputError(
        "cannot start '" + study::own_executable() + "' for " + what
        + (launcher.empty() ? ""
                            : " with 'Study/Launcher = " + launcher + "'"));
    if (outcome.exit_status > 128)
      throw Interrupted(outcome.exit_status - 128,
                        "the study stopped during " + what
                          + "; run it again to resume (finished variants "
                            "are kept)");
    return outcome;
  }


  study::Row
  Study::run_variant(const study::Variant &variant,
                     const std::string    &output,
                     bool                 &reused) const
  {
    namespace fs = std::filesystem;
    std::ostringstream settings_text;
    for (const auto &a : arguments(variant.settings, output))
      settings_text << a << ' ';
    const std::string stamp = output + "/study.txt";
    study::Row        row;
    row.variant = variant;
    reused      = false;
    int exit    = -1;
    if (std::ifstream in(stamp); in)
      {
        std::string line;
        std::getline(in, line);
        if (line == "command " + settings_text.str())
          in >> exit >> row.wall_seconds, reused = static_cast<bool>(in);
      }
    if (!reused)
      {
        const study::RunOutcome outcome
          = launch(variant.settings,
                   output,
                   "variant " + std::to_string(variant.index) + " ("
                     + variant.label + ")");
        exit             = outcome.exit_status;
        row.wall_seconds = outcome.wall_seconds;
        // The stamp last, through a temporary name: it marks the variant
        // as done.
        {
          std::ofstream out(stamp + ".new");
          out << "command " << settings_text.str() << '\n'
              << exit << ' ' << std::setprecision(17) << row.wall_seconds
              << '\n';
        }
        std::error_code ec;
        fs::rename(stamp + ".new", stamp, ec);
      }
    row.finished = exit == 0 && fs::exists(output + "/run.txt");
    row.status   = row.finished ? "finished" : study::describe_exit(exit);
    if (row.finished)
      row.record = output::RunRecord::read(output + "/run.txt");
    return row;
  }


  void
  Study::run()
  {
    setup();
    install_interruption_handlers();
    create_directories();
    const auto                    start = std::chrono::steady_clock::now();
    const std::string             reference_directory = run_reference();
    const std::vector<study::Row> rows
      = run_variants(reference_directory, start);
    const std::string what = quantity.describe();
    write_reports(rows, what);
    if (!picker.tolerances.empty() && picker.tolerances[0] > 0)
      run_choices(rows, what);
    parallel_tools::screen()
      << "study: " << rows.size() << " variants in " << seconds_since(start)
      << " s; results in " << directory << "/results.csv" << std::endl;
  }


  void
  Study::create_directories() const
  {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(directory, ec);
    require(!ec, "Study/Directory", "cannot create '" + directory + "'");
    fs::create_directories(runs_directory, ec);
    require(!ec,
            "Study/Runs directory",
            "cannot create '" + runs_directory + "'");
  }


  std::string
  Study::run_reference() const
  {
    if (quantity.reference != "reference run")
      return "";
    const std::string reference_directory = runs_directory + "/reference";
    parallel_tools::screen() << "study: reference run ("
                             << quantity.reference_settings << ")" << std::endl;
    bool       reused;
    const auto reference
      = run_variant(reference_variant(), reference_directory, reused);
    if (!reference.finished)
      throw SolverError("the reference run did not finish (" + reference.status
                        + "; see " + reference_directory + "/log.txt)");
    return reference_directory;
  }


  std::vector<study::Row>
  Study::run_variants(const std::string                          &reference,
                      const std::chrono::steady_clock::time_point start) const
  {
    auto                   &screen = parallel_tools::screen();
    std::vector<study::Row> rows;
    // Runs made now (not kept from before) and their time, for the
    // estimate of the time left.
    unsigned int ran         = 0;
    double       run_seconds = 0;
    for (const auto &variant : variants)
      {
        const std::string output
          = runs_directory + "/variant-" + std::to_string(variant.index);
        screen << "study: variant " << variant.index << " of "
               << variants.size() << " (" << variant.label << "), "
               << std::fixed << std::setprecision(1) << seconds_since(start)
               << " s elapsed";
        const unsigned int left = variants.size() - variant.index + 1;
        if (ran > 0)
          screen << ", about " << run_seconds / ran * left << " s to go";
        screen << std::defaultfloat << std::setprecision(6) << std::endl;
        bool       reused;
        const auto t0  = seconds_since(start);
        study::Row row = run_variant(variant, output, reused);
        if (!reused)
          {
            ++ran;
            run_seconds += seconds_since(start) - t0;
          }
        if (row.finished)
          row.error
            = study::quantity_error(quantity, output, row.record, reference);
        screen << "  " << (reused ? "kept from before: " : "") << row.status;
        if (row.finished)
          screen << ", " << row.get("unknowns") << " unknowns, "
                 << row.get("wall total") << " s, error " << row.error;
        screen << std::endl;
        rows.push_back(row);
        // A signal to the study alone (not to the running variant) stops it
        // here, between variants.
        if (const int signal = interruption_requested())
          throw Interrupted(signal,
                            "the study stopped after variant "
                              + std::to_string(variant.index)
                              + "; run it again to resume (finished variants "
                                "are kept)");
      }
    return rows;
  }


  void
  Study::write_reports(const std::vector<study::Row> &rows,
                       const std::string             &what) const
  {
    auto &screen = parallel_tools::screen();
    study::write_csv(directory + "/results.csv", axes, rows, what);
    std::ostringstream tables;
    study::write_convergence_tables(
      tables, directory, axes, rows, rate_axis, rates_against, scene_dimension);
    std::ofstream(directory + "/convergence.txt") << tables.str();
    screen << "\n" << what << "\n" << tables.str();
    screen << study::draw_charts(directory, title, axes, rows, rate_axis, what)
           << "\n\n";
    const std::string summary
      = study::summary_paragraph(rows, tolerances, what);
    std::ofstream(directory + "/summary.txt") << summary << '\n';
    screen << summary << "\n" << std::endl;
  }


  void
  Study::run_choices(const std::vector<study::Row> &rows,
                     const std::string             &what) const
  {
    auto         &screen = parallel_tools::screen();
    std::ofstream choices(directory + "/choice.txt");
    unsigned int  k = 0;
    // The choices in brief, and the runs already made for a variant.
    std::ostringstream                  brief;
    std::map<unsigned int, std::string> ran_into;
    for (const double tolerance : picker.tolerances)
      for (const double budget : picker.budgets)
        {
          ++k;
          const auto choice = study::pick(rows, tolerance, budget, what);
          choices << choice.explanation << "\n\n" << std::flush;
          screen << choice.explanation << std::endl;
          brief << "  error <= " << tolerance << ", "
                << (budget > 0 ? "frame " + std::to_string(budget) + " s"
                               : std::string("no budget"))
                << ": "
                << (choice.row
                      ? "#" + std::to_string(rows[*choice.row].variant.index)
                          + " (" + rows[*choice.row].variant.label + ")"
                      : std::string("none"))
                << '\n';
          if (!choice.row || !picker.run_choice)
            continue;
          const unsigned int chosen = rows[*choice.row].variant.index;
          if (ran_into.count(chosen))
            {
              screen << "study: the scene with choice #" << chosen
                     << " ran already, into " << ran_into[chosen] << "\n"
                     << std::endl;
              continue;
            }
          const std::string output = directory + "/choice-" + std::to_string(k);
          ran_into[chosen]         = output;
          screen << "study: running the scene with choice #" << chosen
                 << " into " << output << std::endl;
          const auto outcome
            = launch(rows[*choice.row].variant.settings,
                     output,
                     "the run of choice #" + std::to_string(chosen));
          screen << "  " << study::describe_exit(outcome.exit_status) << " in "
                 << outcome.wall_seconds << " s\n"
                 << std::endl;
        }
    choices << "Choices:\n" << brief.str();
    screen << "Choices:\n" << brief.str() << std::endl;
  }


  // The study does not depend on the dimension: its variants are separate
  // processes that read their own.
  TISSUEFEM_REGISTER_PROBLEM_WITHOUT_DIMENSION(
    Study,
    "study",
    "runs an elasticity scene over variants and charts error against cost "
    "(see 'Study').")
} // namespace tissuefem::study
