// Blocks of hexahedra of the invertible neo-Hookean model recover their
// rest shape from crushed and scrambled starts, many seeds each, by
// elasticity alone: 'Boundary conditions/Self contact pressure =
// automatic' must resolve to 0 on hexahedra, which do not settle tangled
// from these starts (see crushed_starts.h for the starts and the measure).

#include "crushed_starts.h"

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  tissuefem_tests::check_crushed_starts("hypercube", 0.);
  return tissuefem_tests::exit_status();
}
