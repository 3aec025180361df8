// The tissuefem executable: everything lives in the library; see
// tissuefem::run_command_line() for the command line.
#include <deal.II/base/mpi.h>

#include <tissuefem/app/command_line.h>

int
main(int argc, char **argv)
{
  // MPI for the processes (mpirun -np N), and by default as many threads
  // per process as leave every core of the machine busy ('--threads'
  // lowers it).
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv);
  return tissuefem::run_command_line(argc, argv);
}
