#pragma once

#include <string>
#include <vector>

namespace tissuefem
{
  /**
   * Thrown on every process at the same point of a run when the live
   * view's page asks to start again from t = 0 ('reset'): the command line
   * then runs the same parameter file again in the same process (a fresh
   * scene, integrator, tools and output files), with @p overrides added to
   * its --set options (the live view's port, so that the pages reconnect
   * to the same address). Not a std::exception: no error handler takes it
   * for a failure.
   */
  struct ResetRequest
  {
    std::vector<std::string> overrides;
  };
} // namespace tissuefem
