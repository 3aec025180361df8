// The tissuefem executable: everything lives in the library; see
// tissuefem::run_command_line() for the command line.
#include <tissuefem/base/application.h>

int
main(int argc, char **argv)
{
  return tissuefem::run_command_line(argc, argv);
}
