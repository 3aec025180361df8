#include <deal.II/base/mpi.h>

#include <tissuefem/base/interruption.h>
#include <tissuefem/base/parallel.h>

#include <csignal>

namespace tissuefem
{
  namespace
  {
    volatile std::sig_atomic_t received = 0;

    extern "C" void
    record_signal(int signal)
    {
      received = signal;
      // A second signal ends the process at once.
      std::signal(signal, SIG_DFL);
    }
  } // namespace


  void
  install_interruption_handlers()
  {
    std::signal(SIGINT, record_signal);
    std::signal(SIGTERM, record_signal);
  }


  int
  interruption_received_here()
  {
    return static_cast<int>(received);
  }


  int
  interruption_requested()
  {
    return dealii::Utilities::MPI::max(static_cast<int>(received),
                                       parallel_tools::communicator());
  }
} // namespace tissuefem
