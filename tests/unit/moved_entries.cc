// Entries moved to a subsection of their own (base/moved_entries.h) keep
// users' files working: a value at the old place ('Output/Probe points')
// is read at the new one ('Output/Probes/Points'); a file that gives both
// places different values is refused naming the old one; '--set' at either
// place overrides the file at either place. The expected values are the
// ones written into the files below; each old name gets one notice.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/app/parameters.h>
#include <tissuefem/base/input_error.h>

#include "../tests.h"

#include <fstream>
#include <string>
#include <vector>

using namespace dealii;
using namespace tissuefem;

namespace
{
  /// The values of the new places after reading @p text with @p overrides
  /// ("probes | VTU interval | reactions | rest shape"), or the error.
  std::string
  read(const std::string &text, const std::vector<std::string> &overrides = {})
  {
    {
      std::ofstream file("moved.prm");
      file << "set Dimension = 3\n" << text;
    }
    ParameterHandler prm;
    declare_all_parameters(prm);
    try
      {
        read_parameters(prm, "moved.prm", overrides);
      }
    catch (const InputError &e)
      {
        return std::string("error: ") + e.what();
      }
    std::string result;
    prm.enter_subsection("Output");
    for (const auto &[section, name] :
         std::vector<std::pair<std::string, std::string>>{
           {"Probes", "Points"},
           {"VTU", "Interval"},
           {"Reactions", "Boundary ids"},
           {"Final state", "Report rest shape"}})
      {
        prm.enter_subsection(section);
        result += (result.empty() ? "" : " | ") + prm.get(name);
        prm.leave_subsection();
      }
    prm.leave_subsection();
    return result;
  }

  const std::string old_names = "subsection Output\n"
                                "  set Probe points = 1, 2, 3\n"
                                "  set VTU interval = 7\n"
                                "  set Reaction boundary ids = 4, 5\n"
                                "  set Report rest shape = true\n"
                                "end\n";

  const std::string new_names = "subsection Output\n"
                                "  subsection Probes\n"
                                "    set Points = 1, 2, 3\n"
                                "  end\n"
                                "  subsection VTU\n"
                                "    set Interval = 7\n"
                                "  end\n"
                                "  subsection Reactions\n"
                                "    set Boundary ids = 4, 5\n"
                                "  end\n"
                                "  subsection Final state\n"
                                "    set Report rest shape = true\n"
                                "  end\n"
                                "end\n";
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const std::string                expected = "1, 2, 3 | 7 | 4, 5 | true";

  tissuefem_tests::check(read(new_names) == expected,
                         "the new places are read",
                         read(new_names));
  tissuefem_tests::check(read(old_names) == expected,
                         "the old places are read at the new ones",
                         read(old_names));
  tissuefem_tests::check(read(old_names + new_names) == expected,
                         "both places with the same values: accepted",
                         read(old_names + new_names));

  const std::string both = read(old_names
                                + "subsection Output\n  subsection VTU\n"
                                  "    set Interval = 3\n  end\nend\n");
  tissuefem_tests::check(
    both.find("error: Parameter 'Output/VTU interval'") == 0
      && both.find("Output/VTU/Interval") != std::string::npos,
    "both places with different values: refused naming both",
    both);

  const std::string over_new = read(old_names, {"Output/VTU/Interval=2"});
  tissuefem_tests::check(over_new == "1, 2, 3 | 2 | 4, 5 | true",
                         "--set at the new place overrides the old one",
                         over_new);
  const std::string over_old = read(new_names, {"Output/VTU interval=2"});
  tissuefem_tests::check(over_old == "1, 2, 3 | 2 | 4, 5 | true",
                         "--set at the old place overrides the new one",
                         over_old);
  const std::string bad = read(old_names, {"Output/VTU interval=-1"});
  tissuefem_tests::check(bad.find("error: --set 'Output/VTU interval=-1'") == 0,
                         "--set at the old place is checked by the pattern",
                         bad);
  return tissuefem_tests::exit_status();
}
