#include <deal.II/base/mpi.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/tool/live_link.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
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
                     const std::string &port_file)
      : timeout(timeout)
      , dim(dim)
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
  }


  LiveLink::~LiveLink()
  {
    close_client();
    if (listener >= 0)
      ::close(listener);
  }


  void
  LiveLink::close_client()
  {
    if (client >= 0)
      ::close(client);
    client = -1;
  }


  std::vector<LiveLink::Sample>
  LiveLink::read_lines(std::string &reason)
  {
    std::vector<Sample> received;
    const int           wait_ms = static_cast<int>(1000 * timeout);
    if (client < 0)
      {
        pollfd request{listener, POLLIN, 0};
        if (::poll(&request, 1, wait_ms) <= 0)
          {
            reason = "no client connected within 'Tool/Live timeout' ("
                     + std::to_string(timeout) + " s)";
            return received;
          }
        client = ::accept(listener, nullptr, nullptr);
        if (client < 0)
          {
            reason = std::string("accepting the client failed: ")
                     + std::strerror(errno);
            return received;
          }
      }
    while (received.empty())
      {
        std::size_t end;
        while ((end = pending.find('\n')) != std::string::npos)
          {
            std::string line = pending.substr(0, end);
            pending.erase(0, end + 1);
            if (!line.empty() && line.back() == '\r')
              line.pop_back();
            if (line.find_first_not_of(" \t") == std::string::npos)
              continue;
            if (line == "bye")
              {
                reason = "the client said bye";
                return received;
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
                reason = "malformed line from the client: '"
                         + line.substr(0, 80) + "' (expected 't' and "
                         + std::to_string(dim) + " finite coordinates)";
                return received;
              }
            received.push_back(sample);
          }
        if (!received.empty())
          break;
        pollfd request{client, POLLIN, 0};
        if (::poll(&request, 1, wait_ms) <= 0)
          {
            reason = "the client sent nothing for 'Tool/Live timeout' ("
                     + std::to_string(timeout) + " s)";
            return received;
          }
        char          buffer[4096];
        const ssize_t n = ::recv(client, buffer, sizeof(buffer), 0);
        if (n <= 0)
          {
            reason = "the client closed the connection";
            return received;
          }
        pending.append(buffer, n);
        if (pending.size() > (1u << 20))
          {
            reason = "the client sent a line longer than 1 MB";
            return received;
          }
      }
    return received;
  }


  std::vector<LiveLink::Sample>
  LiveLink::receive()
  {
    std::vector<Sample> received;
    std::string         reason;
    if (!has_ended && parallel_tools::is_root())
      {
        if (!send_failure.empty())
          reason = send_failure;
        else
          received = read_lines(reason);
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
        close_client();
      }
    return received;
  }


  void
  LiveLink::send(const double time, const std::vector<double> &force)
  {
    ++answers;
    if (!parallel_tools::is_root() || client < 0 || !send_failure.empty())
      return;
    std::ostringstream line;
    line << std::setprecision(10) << time;
    for (const double f : force)
      line << ' ' << f;
    line << '\n';
    const std::string text = line.str();
    // MSG_NOSIGNAL: a client that went away must not kill the run.
    if (::send(client, text.data(), text.size(), MSG_NOSIGNAL)
        != static_cast<ssize_t>(text.size()))
      {
        send_failure = "the client stopped reading";
        close_client();
      }
  }
} // namespace tissuefem::tool
