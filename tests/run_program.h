// Runs tissuefem's command line inside a unit test, its screen output
// muted, for tests that check what a whole run writes.
#pragma once

#include <tissuefem/app/command_line.h>

#include <mpi.h>

#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace tissuefem_tests
{
  /// tissuefem @p arguments (without the program's name) with std::cout
  /// muted; every process waits for the others before it returns the exit
  /// status, so that process 0 may read what the run wrote.
  inline int
  run_program(std::vector<std::string> arguments)
  {
    arguments.insert(arguments.begin(), "tissuefem");
    std::vector<char *> argv;
    for (auto &a : arguments)
      argv.push_back(a.data());
    std::ostringstream muted;
    std::streambuf    *screen = std::cout.rdbuf(muted.rdbuf());
    const int status = tissuefem::run_command_line(argv.size(), argv.data());
    std::cout.rdbuf(screen);
    MPI_Barrier(MPI_COMM_WORLD);
    return status;
  }
} // namespace tissuefem_tests
