// The command-line program: options, running a parameter file, exit status.
#include <deal.II/base/multithread_info.h>

#include <tissuefem/app/command_line.h>
#include <tissuefem/app/parameters.h>
#include <tissuefem/base/input_error.h>
#include <tissuefem/base/interruption.h>
#include <tissuefem/base/moved_entries.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/base/reset_request.h>
#include <tissuefem/materials/consistency_check.h>
#include <tissuefem/materials/material_set.h>
#include <tissuefem/problems/interface.h>

#include <filesystem>
#include <iostream>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#ifndef TISSUEFEM_VERSION
#define TISSUEFEM_VERSION "unknown"
#endif
namespace tissuefem
{
  namespace
  {
    /// Checks every material a parameter file uses, in its dimension; with
    /// @p every_registered, every registered model instead, with the
    /// elastic constants of the file's first material (and the file's
    /// model subsections and fibre direction): a list that grows by itself.
    template <int dim>
    bool
    check_materials(ParameterHandler &prm, const bool every_registered)
    {
      materials::MaterialParameters parameters;
      parameters.parse_parameters(prm);
      if (every_registered)
        {
          const auto constants = parameters.constants[0];
          parameters.model_names.clear();
          parameters.constants.clear();
          parameters.material_ids.clear();
          for (const auto &[name, entry] :
               materials::MaterialRegistry<dim>::instance().all())
            {
              parameters.model_names.push_back(name);
              parameters.constants.push_back(constants);
            }
        }
      std::vector<materials::ConsistencyReport> reports;
      for (unsigned int i = 0; i < parameters.model_names.size(); ++i)
        {
          const auto model
            = materials::MaterialRegistry<dim>::instance().create(
              parameters.model_names[i], parameters.constants[i], prm);
          std::string label = parameters.model_names[i];
          if (!parameters.material_ids.empty())
            label += " (id " + std::to_string(parameters.material_ids[i]) + ")";
          reports.push_back(materials::check_consistency<dim>(
            label, *model, parameters.constants[i].mu));
        }
      materials::print_consistency_table(parallel_tools::screen(), reports);
      bool all = true;
      for (const auto &r : reports)
        all = all && r.passes();
      return all;
    }


    /// One line on standard error, from process 0 only.
    void
    report_error(const std::string &line)
    {
      if (parallel_tools::is_root())
        std::cerr << line << std::endl;
    }


    void
    print_usage(std::ostream &out)
    {
      out
        << "Usage:\n"
           "  tissuefem FILE.prm [--set 'Subsection/Name=value' ...]\n"
           "      run the scene FILE.prm describes; each --set overrides one\n"
           "      parameter after the file is read.\n"
           "  tissuefem --validate FILE.prm [--set ...]\n"
           "      check the file (parameters, mesh, expressions, probes)\n"
           "      without computing or writing anything.\n"
           "  tissuefem --check-material FILE.prm [--set ...]\n"
           "      check each material the file uses against its own energy\n"
           "      (finite differences, Taylor slopes, tangent methods,\n"
           "      symmetry, frame indifference) and print a table.\n"
           "  tissuefem --check-all-materials FILE.prm [--set ...]\n"
           "      the same for every registered model, with the elastic\n"
           "      constants of the file's first material.\n"
           "  tissuefem --print-parameters\n"
           "      list every parameter with its default and documentation.\n"
           "  tissuefem --help | --version\n"
           "Options for runs:\n"
           "  --threads N   use at most N threads per process (default: all\n"
           "                cores of the machine shared among the processes)\n"
           "  --restart DIR continue the run from the checkpoint in DIR (see\n"
           "                'Output/Checkpoint interval'); with the same\n"
           "                FILE.prm and process count the outputs equal\n"
           "                those of an uninterrupted run\n"
           "  --view        show the run in a web browser as it goes (the\n"
           "                same as --set 'Output/Live view/Port=0'; the\n"
           "                address is printed)\n"
           "SIGINT and SIGTERM end a run after the current step, with its\n"
           "outputs and a checkpoint written.\n"
           "Parallel runs: mpirun -np P tissuefem FILE.prm\n"
           "Exit status: 0 on success, 2 for bad input, 3 when the solver\n"
           "fails, 4 for any other error, 128 + N after signal N (130 for\n"
           "SIGINT, 143 for SIGTERM).\n";
    }

    /// What the command line asks for.
    struct CommandLine
    {
      std::vector<std::string> overrides;
      std::string              file, restart;
      bool                     validate_only = false, check_material = false,
           check_all_materials = false;
      /// The exit status when an option was answered at once (--help,
      /// --version, --print-parameters): nothing more is to be done.
      std::optional<int> finished;
    };

    /// Reads the options in order, so that an option answered at once
    /// ends the reading there (as a bad option before it throws first).
    CommandLine
    read_command_line(const std::vector<std::string> &args)
    {
      CommandLine line;
      for (unsigned int i = 0; i < args.size(); ++i)
        {
          const std::string &a = args[i];
          if (a == "--help" || a == "-h")
            {
              print_usage(parallel_tools::screen());
              line.finished = 0;
              return line;
            }
          if (a == "--version")
            {
              parallel_tools::screen()
                << "tissuefem " << TISSUEFEM_VERSION << std::endl;
              line.finished = 0;
              return line;
            }
          if (a == "--print-parameters")
            {
              ParameterHandler prm;
              declare_all_parameters(prm);
              prm.print_parameters(parallel_tools::screen(),
                                   ParameterHandler::PRM);
              line.finished = 0;
              return line;
            }
          if (a == "--threads")
            {
              if (i + 1 == args.size())
                throw InputError("--threads needs a number >= 1");
              const std::string n = args[++i];
              if (n.empty()
                  || n.find_first_not_of("0123456789") != std::string::npos
                  || n.size() > 4 || std::stoi(n) < 1)
                throw InputError("--threads '" + n
                                 + "': expected a number >= 1");
              MultithreadInfo::set_thread_limit(std::stoi(n));
              continue;
            }
          if (a == "--restart")
            {
              if (i + 1 == args.size())
                throw InputError("--restart needs a checkpoint directory");
              line.restart = args[++i];
              continue;
            }
          if (a == "--validate")
            line.validate_only = true;
          else if (a == "--check-material")
            line.check_material = true;
          else if (a == "--check-all-materials")
            line.check_material = line.check_all_materials = true;
          else if (a == "--set")
            {
              if (i + 1 == args.size())
                throw InputError("--set needs 'Subsection/Name=value'");
              line.overrides.push_back(args[++i]);
            }
          else if (a == "--view")
            line.overrides.push_back("Output/Live view/Port=0");
          else if (a.rfind("--set=", 0) == 0)
            line.overrides.push_back(a.substr(6));
          else if (a.rfind("--", 0) == 0)
            throw InputError("unknown option '" + a + "' (see --help)");
          else if (line.file.empty())
            line.file = a;
          else
            throw InputError("more than one parameter file given ('" + line.file
                             + "', '" + a + "')");
        }
      return line;
    }

    /// Reads the parameter file and checks, validates or runs what it
    /// describes; returns the exit status. Errors are thrown.
    int
    run_parameter_file(const CommandLine &line)
    {
      if (line.file.empty())
        {
          if (parallel_tools::is_root())
            print_usage(std::cerr);
          return 2;
        }

      ParameterHandler prm;
      declare_parameters_for(prm, line.file, line.overrides);
      read_parameters(prm, line.file, line.overrides);
      if (line.check_material)
        {
          const int  dim = prm.get_integer("Dimension");
          const bool all = line.check_all_materials;
          const bool ok  = dim == 1   ? check_materials<1>(prm, all)
                           : dim == 2 ? check_materials<2>(prm, all)
                                      : check_materials<3>(prm, all);
          return ok ? 0 : 3;
        }
      problems::RunContext context;
      context.parameter_directory
        = std::filesystem::path(line.file).parent_path().string();
      context.restart_directory = line.restart;
      context.parameter_file    = line.file;
      auto problem              = problems::ProblemRegistry::instance().create(
        problems::ProblemRegistry::instance().canonical(prm.get("Problem"),
                                                        "Problem"),
        prm,
        context);
      if (line.validate_only)
        {
          problem->setup();
          parallel_tools::screen()
            << "tissuefem: '" << line.file << "' is valid" << std::endl;
          return 0;
        }
      parallel_tools::screen()
        << "tissuefem: " << parallel_tools::n_processes()
        << " MPI process(es), " << MultithreadInfo::n_threads()
        << " thread(s) each" << std::endl;
      problem->run();
      return 0;
    }
  } // namespace


  int
  run_command_line(int argc, char **argv)
  {
    const std::vector<std::string> args(argv + 1, argv + argc);
    try
      {
        CommandLine line = read_command_line(args);
        if (line.finished)
          return *line.finished;
        for (;;)
          try
            {
              return run_parameter_file(line);
            }
          catch (const ResetRequest &reset)
            {
              // The same file from t = 0 (not from a checkpoint), keeping
              // the live view's address.
              line.restart.clear();
              line.overrides.insert(line.overrides.end(),
                                    reset.overrides.begin(),
                                    reset.overrides.end());
              parallel_tools::screen()
                << "tissuefem: reset from the live view: the run starts "
                   "again from t = 0"
                << std::endl;
            }
      }
    catch (const Interrupted &e)
      {
        report_error("tissuefem: interrupted: " + std::string(e.what()));
        return 128 + e.signal;
      }
    // Every process meets the same errors (all check the same input and
    // take part in the same collective operations); process 0 reports.
    catch (const InputError &e)
      {
        report_error("tissuefem: error: " + std::string(e.what()));
        return 2;
      }
    catch (const SolverError &e)
      {
        report_error("tissuefem: solver failure: " + std::string(e.what()));
        return 3;
      }
    catch (const ExceptionBase &e)
      {
        report_error("tissuefem: error: " + one_line_message(e));
        return 4;
      }
    catch (const std::exception &e)
      {
        report_error("tissuefem: error: " + squeeze_whitespace(e.what()));
        return 4;
      }
  }
} // namespace tissuefem
