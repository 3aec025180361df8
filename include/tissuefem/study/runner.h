#pragma once

#include <string>
#include <vector>

namespace tissuefem::study
{
  /// How one child run ended, as the study saw it from outside.
  struct RunOutcome
  {
    /// The child's exit status (128 + n for a signal n).
    int exit_status = 0;
    /// Wall time from start to end of the child process (s).
    double wall_seconds = 0;
    /// Largest resident set of the child (MB; of the launcher with a
    /// launcher such as mpirun, so the run's own record is preferred).
    double peak_memory_mb = 0;
  };

  /**
   * Runs @p executable with @p arguments (prefixed by the whitespace-
   * separated words of @p launcher, if any) as a child process, its
   * standard output and error into @p log_file, and waits for it. Ctrl-C
   * reaches the child too (same process group): it finishes its step and
   * ends with 128 + the signal, which the study takes as the order to stop.
   */
  RunOutcome
  run_child(const std::string              &executable,
            const std::vector<std::string> &arguments,
            const std::string              &launcher,
            const std::string              &log_file);

  /// The running executable's own path (to start tissuefem again).
  std::string
  own_executable();

  /// What an exit status of tissuefem means, in words.
  std::string
  describe_exit(const int status);
} // namespace tissuefem::study
