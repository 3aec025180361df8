#pragma once

#include <stdexcept>
#include <string>

namespace tissuefem
{
  /**
   * SIGINT and SIGTERM end a run in order: the handler only records the
   * signal; the run checks at the end of each step (all processes agree:
   * the request is reduced over MPI), writes the outputs of that step and a
   * checkpoint, and stops with exit status 128 + the signal number.
   */
  void
  install_interruption_handlers();

  /// The signal received (SIGINT or SIGTERM) on any process, 0 if none.
  /// Collective: every process must call it at the same point.
  int
  interruption_requested();

  /// The signal this process received, 0 if none; not collective (for a
  /// process that waits alone, such as the live view's pause).
  int
  interruption_received_here();

  /// Thrown after an interrupted run has written its outputs.
  class Interrupted : public std::runtime_error
  {
  public:
    Interrupted(const int signal, const std::string &what)
        : std::runtime_error(what)
        , signal(signal)
    {
    }
    int signal;
  };
} // namespace tissuefem
