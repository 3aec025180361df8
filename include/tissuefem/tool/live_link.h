#pragma once

#include <string>
#include <vector>

namespace tissuefem::tool
{
  /**
   * A haptic device or game engine driving the tool live, over a TCP
   * connection on the loopback interface (127.0.0.1 only: the simulation
   * and the device driver run on one machine). Text lines both ways:
   *
   *   client -> tissuefem   "t x y z"     tool position at time t
   *                                       (dim coordinates, whitespace
   *                                       separated, times increasing)
   *   tissuefem -> client   "t fx fy fz"  force of the tissue on the tool
   *                                       at that time, one line per
   *                                       position received
   *
   * and "bye" (or closing the connection) ends the session. Process 0
   * talks to the client; every process gets the samples. A client that
   * does not connect, or sends nothing, within the timeout, closes the
   * connection, or sends a malformed line ends the session: ended() turns
   * true with reason(); the run then finishes cleanly with what it has.
   */
  class LiveLink
  {
  public:
    struct Sample
    {
      double              time;
      std::vector<double> position;
    };

    /// Listens on 127.0.0.1:@p port (0: any free port) and writes the
    /// port number to @p port_file (complete, then renamed into place) so
    /// that a client can find it. Throws InputError if it cannot listen.
    LiveLink(int                port,
             double             timeout,
             unsigned int       dim,
             const std::string &port_file);
    ~LiveLink();

    /// Blocks until at least one position arrived (accepting the client
    /// first if need be) or the session ended; collective.
    std::vector<Sample>
    receive();

    /// Sends "t f..." to the client (process 0; others do nothing).
    void
    send(double time, const std::vector<double> &force);

    bool
    ended() const
    {
      return has_ended;
    }
    const std::string &
    reason() const
    {
      return end_reason;
    }
    /// Positions received and answers sent so far.
    unsigned int samples = 0, answers = 0;

  private:
    double       timeout;
    unsigned int dim;
    int          listener = -1, client = -1;
    std::string  pending; // bytes of an incomplete line
    bool         has_ended = false;
    std::string  end_reason;
    /// Set on process 0 when sending failed; shared at the next receive().
    std::string send_failure;

    /// Process 0's part of receive(): the lines, or an end reason.
    std::vector<Sample>
    read_lines(std::string &reason);
    void
    close_client();
  };
} // namespace tissuefem::tool
