// Blocks of tetrahedra of the invertible neo-Hookean model from crushed and
// scrambled starts, many seeds each (crushed_starts.h has the starts and
// the measure). Every run must complete. The rest shape must come back
// from exact collapses, from nearly a plane and from smooth scrambles;
// from nodes within 1 % of a line or a point and from random scrambles of
// two cell sizes the tetrahedra settle in tangled equilibria (measured:
// 9 of 18 starts, doc/tests.md), which no remedy tried so far removes:
// those runs must complete, and the tangle must be measured: the final
// state's tangled share of the volume (solid/self_overlap.h: inverted, or
// overlapping the body elsewhere) above 0. Measured 0.005 to 0.78; six of
// the nine are fold-overs with every det F > 0, which only the winding
// number of the deformed boundary sees.

#include "crushed_starts.h"

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  tissuefem_tests::check_crushed_starts("simplex", [](const std::string &name) {
    return name.find("collapsed") == 0 || name.find("nearly a plane") == 0
           || name.find("smooth") == 0;
  });
  return tissuefem_tests::exit_status();
}
