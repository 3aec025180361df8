#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <iostream>
#include <string>

namespace tissuefem
{
  using namespace dealii;

  /// The distributed vector every solid operator and integrator works with:
  /// locally owned entries, optionally with read-only ghost entries.
  using VectorType = TrilinosWrappers::MPI::Vector;
  /// The distributed sparse matrix of Jacobians and mass matrices.
  using MatrixType = TrilinosWrappers::SparseMatrix;

  namespace parallel_tools
  {
    /// The communicator of a run: all processes share one mesh.
    inline MPI_Comm
    communicator()
    {
      return MPI_COMM_WORLD;
    }

    inline unsigned int
    n_processes()
    {
      return Utilities::MPI::n_mpi_processes(communicator());
    }

    inline bool
    is_root()
    {
      return Utilities::MPI::this_mpi_process(communicator()) == 0;
    }

    /**
     * The screen: std::cout on process 0 and a stream that discards
     * everything on the others, so that each message is printed once.
     */
    std::ostream &
    screen();

    /**
     * The first non-empty @p local_error of any process (by rank), on every
     * process; empty if there is none. Collective: lets every process fail
     * alike when only some met an error.
     */
    std::string
    first_error(const std::string &local_error);
  } // namespace parallel_tools
} // namespace tissuefem
