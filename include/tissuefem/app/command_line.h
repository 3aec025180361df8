#pragma once

namespace tissuefem
{
  /// The command-line program; returns the process exit status.
  int
  run_command_line(int argc, char **argv);
} // namespace tissuefem
