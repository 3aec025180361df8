#include <tissuefem/base/input_error.h>
#include <tissuefem/base/interruption.h>
#include <tissuefem/study/runner.h>

#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <sstream>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>

namespace tissuefem::study
{
  std::string
  own_executable()
  {
    std::error_code ec;
    const auto      path = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec)
      throw InputError("cannot find the tissuefem executable through "
                       "/proc/self/exe to run a study's variants");
    // A rebuilt executable replaces the running one's file: its new file
    // has the same path.
    std::string       name     = path.string();
    const std::string replaced = " (deleted)";
    if (name.size() > replaced.size()
        && name.compare(name.size() - replaced.size(),
                        replaced.size(),
                        replaced)
             == 0)
      name.resize(name.size() - replaced.size());
    return name;
  }


  RunOutcome
  run_child(const std::string              &executable,
            const std::vector<std::string> &arguments,
            const std::string              &launcher,
            const std::string              &log_file)
  {
    std::vector<std::string> words;
    {
      std::istringstream in(launcher);
      for (std::string w; in >> w;)
        words.push_back(w);
    }
    words.push_back(executable);
    words.insert(words.end(), arguments.begin(), arguments.end());
    std::vector<char *> argv;
    for (auto &w : words)
      argv.push_back(w.data());
    argv.push_back(nullptr);

    const int log
      = ::open(log_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (log < 0)
      throw InputError("Study/Directory: cannot write '" + log_file + "'");
    const auto  start = std::chrono::steady_clock::now();
    const pid_t child = ::fork();
    if (child < 0)
      {
        ::close(log);
        throw InputError("cannot start a process for a study variant");
      }
    if (child == 0)
      {
        // The child: its own process group would hide terminal signals, so
        // it stays in ours and the study forwards what it records.
        ::dup2(log, STDOUT_FILENO);
        ::dup2(log, STDERR_FILENO);
        ::close(log);
        ::execvp(argv[0], argv.data());
        ::_exit(127);
      }
    ::close(log);
    int           status = 0;
    struct rusage usage;
    while (::wait4(child, &status, 0, &usage) < 0)
      if (errno != EINTR)
        throw InputError("lost the process of a study variant");
    RunOutcome outcome;
    outcome.wall_seconds
      = std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
    outcome.peak_memory_mb = usage.ru_maxrss / 1024.;
    outcome.exit_status    = WIFEXITED(status)     ? WEXITSTATUS(status)
                             : WIFSIGNALED(status) ? 128 + WTERMSIG(status)
                                                   : 255;
    return outcome;
  }


  std::string
  describe_exit(const int status)
  {
    switch (status)
      {
        case 0:
          return "finished";
        case 2:
          return "bad input (exit 2)";
        case 3:
          return "solver failure (exit 3)";
        case 4:
          return "error (exit 4)";
        case 127:
          return "could not start (exit 127)";
        default:
          return status > 128
                   ? "ended by signal " + std::to_string(status - 128)
                   : "exit " + std::to_string(status);
      }
  }
} // namespace tissuefem::study
