#pragma once

#include <tissuefem/base/parallel.h>

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace tissuefem::output
{
  /**
   * Everything a run needs to continue bit-identically besides the
   * vectors: where it was, what the integrator and the output writer
   * carry from step to step. Doubles are written in hexadecimal floating
   * point, so they come back exactly.
   */
  struct Checkpoint
  {
    unsigned int  step        = 0;
    double        time        = 0;
    unsigned int  n_processes = 1;
    std::uint64_t n_dofs      = 0;
    /// Written by processes each holding only its own cells ('Geometry/Mesh
    /// distribution = distributed'), which number the unknowns of a process
    /// in another order than a shared mesh does.
    bool                distributed_mesh = false;
    std::string         integrator;
    std::vector<double> integrator_scalars;
    /// Output file -> its size in bytes at the checkpoint; a restart cuts
    /// the files back to these sizes and appends.
    std::map<std::string, std::uintmax_t> file_sizes;
    /// What each postprocessor carries from step to step, as lines of
    /// text of its own making (no line breaks), by postprocessor name.
    std::map<std::string, std::vector<std::string>> postprocessor_state;
  };

  /// @p value as text that exact_value() turns back into the same double
  /// (hexadecimal floating point), for postprocessor_state.
  std::string
  exact_text(const double value);

  /// The double exact_text() wrote.
  double
  exact_value(const std::string &text);

  /**
   * Writes @p checkpoint and the locally owned entries of @p vectors
   * (every process its own file) into @p directory, atomically: into
   * '@p directory.new', which then replaces @p directory. Collective.
   */
  void
  write_checkpoint(const std::string                     &directory,
                   const Checkpoint                      &checkpoint,
                   const std::vector<const VectorType *> &vectors);

  /**
   * Reads a checkpoint written by write_checkpoint() into @p vectors, which
   * must have the layout of the run that wrote it (same mesh, process
   * count). Throws InputError naming the directory and what does not match.
   * Collective.
   */
  Checkpoint
  read_checkpoint(const std::string               &directory,
                  const std::vector<VectorType *> &vectors);
} // namespace tissuefem::output
