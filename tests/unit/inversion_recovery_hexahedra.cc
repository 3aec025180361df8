// Blocks of hexahedra of the invertible neo-Hookean model recover their
// rest shape from crushed and scrambled starts, many seeds each: see
// crushed_starts.h for the starts and the measure.

#include "crushed_starts.h"

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  tissuefem_tests::check_crushed_starts("hypercube", [](const std::string &) {
    return true;
  });
  return tissuefem_tests::exit_status();
}
