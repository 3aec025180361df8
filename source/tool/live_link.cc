#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/tool/live_link.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace tissuefem::tool
{
  LiveLink::LiveLink(const int          port,
                     const double       timeout,
                     const unsigned int dim,
                     const double       period,
                     const Limits      &limits,
                     const std::string &port_file,
                     const bool         reserve_core)
      : timeout(timeout)
      , dim(dim)
      , period(period)
      , limits(limits)
  {
    int bound_port = 0;
    if (parallel_tools::is_root())
      {
        listener = ::socket(AF_INET, SOCK_STREAM, 0);
        int yes  = 1;
        ::setsockopt(listener, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
        sockaddr_in address{};
        address.sin_family      = AF_INET;
        address.sin_port        = htons(static_cast<uint16_t>(port));
        address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        socklen_t length        = sizeof(address);
        if (listener < 0
            || ::bind(listener,
                      reinterpret_cast<sockaddr *>(&address),
                      sizeof(address))
                 != 0
            || ::listen(listener, 1) != 0
            || ::getsockname(listener,
                             reinterpret_cast<sockaddr *>(&address),
                             &length)
                 != 0)
          bound_port = -errno;
        else
          bound_port = ntohs(address.sin_port);
      }
    bound_port = Utilities::MPI::broadcast(parallel_tools::communicator(),
                                           bound_port,
                                           0);
    require(bound_port > 0,
            "Tool/Live port",
            "cannot listen on 127.0.0.1:" + std::to_string(port) + " ("
              + std::strerror(-bound_port) + ")");
    if (parallel_tools::is_root())
      {
        const std::string partial = port_file + ".part";
        {
          std::ofstream out(partial);
          out << bound_port << '\n';
        }
        std::rename(partial.c_str(), port_file.c_str());
      }
    parallel_tools::screen()
      << "tool: waiting for the live client on 127.0.0.1:" << bound_port
      << " (lines 't x y z'; port also in " << port_file << ")" << std::endl;
    if (parallel_tools::is_root())
      worker = std::thread([this] { serve(); });
    // On two cores with both simulating, the client saw answers 1.3-1.6 ms
    // late at the 99th percentile (the thread waited for a core); with one
    // core left to it, 0.27 ms (doc/studies.md).
    // Every core is taken when the processes' threads fill the node (the
    // processes are taken to share one).
    const unsigned int threads = MultithreadInfo::n_threads();
    const unsigned int processes
      = Utilities::MPI::n_mpi_processes(parallel_tools::communicator());
    if (reserve_core && parallel_tools::is_root() && threads > 1
        && threads * processes >= MultithreadInfo::n_cores())
      {
        restored_threads = threads;
        MultithreadInfo::set_thread_limit(threads - 1);
        parallel_tools::screen()
          << "tool: the simulation uses " << threads - 1 << " of " << threads
          << " threads while the live client is served, leaving a core to "
             "its answers ('Live reserved core')"
          << std::endl;
      }
  }


  LiveLink::~LiveLink()
  {
    stop = true;
    if (worker.joinable())
      worker.join();
    if (restored_threads > 0)
      MultithreadInfo::set_thread_limit(restored_threads);
    close_client();
    if (listener >= 0)
      ::close(listener);
  }


  bool
  LiveLink::wait_readable(const int fd)
  {
    // Slices of 20 ms, so that the destructor's stop ends the wait soon.
    const auto start = std::chrono::steady_clock::now();
    while (!stop)
      {
        pollfd    request{fd, POLLIN, 0};
        const int ready = ::poll(&request, 1, 20);
        if (ready > 0)
          return true;
        if (ready < 0 && errno != EINTR)
          return false;
        if (std::chrono::duration<double>(std::chrono::steady_clock::now()
                                          - start)
              .count()
            >= timeout)
          return false;
      }
    return false;
  }


  void
  LiveLink::serve()
  {
    std::string reason;
    if (!wait_readable(listener))
      reason = "no client connected within 'Tool/Live timeout' ("
               + std::to_string(timeout) + " s)";
    else if ((client = ::accept(listener, nullptr, nullptr)) < 0)
      reason
        = std::string("accepting the client failed: ") + std::strerror(errno);
    else
      {
        // Each answer leaves at once: without this, Nagle's algorithm holds
        // it until the client's next position acknowledges the previous
        // one (measured: 2 ms median, 45 ms worst on the loopback).
        int yes = 1;
        ::setsockopt(client, IPPROTO_TCP, TCP_NODELAY, &yes, sizeof(yes));
      }
    while (reason.empty())
      {
        if (!wait_readable(client))
          {
            reason = stop ? "the run ended"
                          : "the client sent nothing for 'Tool/Live timeout' ("
                              + std::to_string(timeout) + " s)";
            break;
          }
        char          buffer[4096];
        const ssize_t n = ::recv(client, buffer, sizeof(buffer), 0);
        if (n <= 0)
          {
            reason = "the client closed the connection";
            break;
          }
        pending.append(buffer, n);
        if (pending.size() > (1u << 20))
          {
            reason = "the client sent a line longer than 1 MB";
            break;
          }
        answer_lines(reason);
      }
    std::lock_guard<std::mutex> guard(lock);
    thread_end  = reason;
    thread_done = true;
    // How far the simulation (its last recorded step) was behind the
    // client's clock when the client stopped.
    lag_at_end = std::max(0., latest_client_time - model.time);
    arrived.notify_all();
  }


  std::string
  LiveLink::refusal(const Sample &sample)
  {
    // Scaled, so that positions near the largest double do not overflow.
    const auto distance
      = [this](const std::vector<double> &a, const std::vector<double> &b) {
          double largest = 0;
          for (unsigned int i = 0; i < dim; ++i)
            largest = std::max(largest, std::abs(a[i] - b[i]));
          if (largest == 0 || !std::isfinite(largest))
            return largest;
          double sum = 0;
          for (unsigned int i = 0; i < dim; ++i)
            sum += std::pow((a[i] - b[i]) / largest, 2);
          return largest * std::sqrt(sum);
        };
    std::ostringstream why;
    why << std::setprecision(4);
    {
      std::lock_guard<std::mutex> guard(lock);
      if (origin.empty())
        origin = sample.position;
      const double from_origin = distance(sample.position, origin);
      if (!(from_origin <= limits.displacement))
        why << "it lies " << from_origin
            << " from the first position, more than the limit "
            << limits.displacement << " (length units)";
    }
    if (why.str().empty() && !last_followed.empty())
      {
        const double jump = distance(sample.position, last_followed);
        if (!(jump <= limits.jump))
          why << "it jumps " << jump
              << " from the last position followed, more than the limit "
              << limits.jump << " (length units)";
      }
    if (why.str().empty())
      last_followed = sample.position;
    return why.str();
  }


  bool
  LiveLink::send_line(const std::string &line)
  {
    const std::string text = line + '\n';
    // MSG_NOSIGNAL: a client that went away must not kill the run.
    return ::send(client, text.data(), text.size(), MSG_NOSIGNAL)
           == static_cast<ssize_t>(text.size());
  }


  std::vector<double>
  LiveLink::force_at(const double time, const std::vector<double> &position)
  {
    std::vector<double>         f(dim, 0.);
    std::lock_guard<std::mutex> guard(lock);
    if (!model.valid || !model.holding)
      return f;
    for (unsigned int i = 0; i < dim; ++i)
      {
        f[i] = model.force[i] + model.rate[i] * (time - model.time);
        for (unsigned int j = 0; j < dim; ++j)
          f[i] += model.stiffness[i * dim + j]
                  * (position[j] - origin[j] - model.position[j]);
      }
    return f;
  }


  void
  LiveLink::set_model(const ForceModel &new_model)
  {
    if (!parallel_tools::is_root())
      return;
    std::lock_guard<std::mutex> guard(lock);
    model = new_model;
  }


  void
  LiveLink::close_client()
  {
    if (client >= 0)
      ::close(client);
    client = -1;
  }


  bool
  LiveLink::answer_lines(std::string &reason)
  {
    std::size_t end;
    while ((end = pending.find('\n')) != std::string::npos)
      {
        const auto  read = std::chrono::steady_clock::now();
        std::string line = pending.substr(0, end);
        pending.erase(0, end + 1);
        if (!line.empty() && line.back() == '\r')
          line.pop_back();
        if (line.find_first_not_of(" \t") == std::string::npos)
          continue;
        if (line == "bye")
          {
            reason = "the client said bye";
            return false;
          }
        std::istringstream in(line);
        Sample             sample;
        sample.position.resize(dim);
        in >> sample.time;
        for (auto &x : sample.position)
          in >> x;
        std::string rest;
        bool        finite = std::isfinite(sample.time);
        for (const double x : sample.position)
          finite = finite && std::isfinite(x);
        if (in.fail() || (in >> rest) || !finite)
          {
            reason = "malformed line from the client: '" + line.substr(0, 80)
                     + "' (expected 't' and " + std::to_string(dim)
                     + " finite coordinates)";
            return false;
          }
        if (const std::string why = refusal(sample); !why.empty())
          {
            if (!send_line("refused " + line.substr(0, 80) + ": " + why))
              {
                reason = "the client stopped reading";
                return false;
              }
            std::lock_guard<std::mutex> guard(lock);
            if (refused++ == 0)
              first_refusal = "'" + line.substr(0, 80) + "': " + why;
            continue;
          }
        // Answer first: the device is waiting.
        std::ostringstream answer;
        answer << std::setprecision(10) << sample.time;
        for (const double f : force_at(sample.time, sample.position))
          answer << ' ' << f;
        if (!send_line(answer.str()))
          {
            reason = "the client stopped reading";
            return false;
          }
        const double latency = std::chrono::duration<double>(
                                 std::chrono::steady_clock::now() - read)
                                 .count();
        std::lock_guard<std::mutex> guard(lock);
        latencies.push_back(latency);
        if (step_running)
          ++during_steps;
        latest_client_time = std::max(latest_client_time, sample.time);
        queue.push_back(std::move(sample));
        arrived.notify_all();
      }
    return true;
  }


  std::vector<LiveLink::Sample>
  LiveLink::receive()
  {
    std::vector<Sample> received;
    std::string         reason;
    if (!has_ended && parallel_tools::is_root())
      {
        std::unique_lock<std::mutex> guard(lock);
        arrived.wait(guard, [this] { return !queue.empty() || thread_done; });
        received.assign(queue.begin(), queue.end());
        queue.clear();
        // Positions that came before the end are still followed.
        if (received.empty())
          reason = thread_end;
      }
    // Every process follows the same trajectory: share the samples.
    std::vector<double> flat;
    for (const auto &s : received)
      {
        flat.push_back(s.time);
        flat.insert(flat.end(), s.position.begin(), s.position.end());
      }
    flat = Utilities::MPI::broadcast(parallel_tools::communicator(), flat, 0);
    reason
      = Utilities::MPI::broadcast(parallel_tools::communicator(), reason, 0);
    received.clear();
    for (std::size_t i = 0; i + dim < flat.size(); i += dim + 1)
      received.push_back(Sample{
        flat[i],
        std::vector<double>(flat.begin() + i + 1, flat.begin() + i + 1 + dim)});
    samples += received.size();
    if (!reason.empty() && !has_ended)
      {
        has_ended  = true;
        end_reason = reason;
      }
    return received;
  }


  std::vector<double>
  LiveLink::recent_latency() const
  {
    std::vector<double> recent;
    {
      std::lock_guard<std::mutex> guard(lock);
      const std::size_t n = std::min<std::size_t>(latencies.size(), 1000);
      recent.assign(latencies.end() - n, latencies.end());
    }
    if (recent.empty())
      return {};
    std::sort(recent.begin(), recent.end());
    return {1e3 * recent[recent.size() / 2],
            1e3
              * recent[std::min<std::size_t>(recent.size() - 1,
                                             0.99 * recent.size())]};
  }


  std::string
  LiveLink::report(const double simulated_time) const
  {
    std::lock_guard<std::mutex> guard(lock);
    std::vector<double>         sorted(latencies);
    std::sort(sorted.begin(), sorted.end());
    auto quantile = [&](const double q) {
      return sorted.empty()
               ? 0.
               : 1e3
                   * sorted[std::min<std::size_t>(sorted.size() - 1,
                                                  q * sorted.size())];
    };
    const auto within
      = std::upper_bound(sorted.begin(), sorted.end(), period) - sorted.begin();
    std::ostringstream s;
    s << std::setprecision(3) << sorted.size()
      << " positions answered from the force model while steps run; answer "
         "latency (reading a position to sending its force, ms): median "
      << quantile(0.5) << ", 99th percentile " << quantile(0.99) << ", max "
      << (sorted.empty() ? 0. : 1e3 * sorted.back()) << "; "
      << (sorted.empty() ? 100. : 100. * within / sorted.size())
      << " % within one haptic period (" << 1e3 * period << " ms); "
      << during_steps << " answered while a step ran; when the client "
      << "stopped the simulation was "
      << (thread_done ? lag_at_end
                      : std::max(0., latest_client_time - simulated_time))
      << " time units behind its latest time";
    if (refused > 0)
      s << "; refused " << refused << " position" << (refused > 1 ? "s" : "")
        << " (not followed; the first " << first_refusal << ")";
    return s.str();
  }
} // namespace tissuefem::tool
