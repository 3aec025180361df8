#pragma once

#include <atomic>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
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
   * and "bye" (or closing the connection) ends the session.
   *
   * Answers never wait for the simulation: on process 0 a communication
   * thread reads each position and answers it at once from the latest
   * force model (set_model(): the last simulated force plus the secant
   * stiffness times the tool's motion since, or its rate times the time
   * since), while the simulation steps on the other threads. The positions
   * are queued for the simulation, whose receive() waits until some
   * arrive: the simulation is paced by the client's clock and never runs
   * ahead of it. Every process gets the samples. A client that does not
   * connect, or sends nothing, within the timeout, closes the connection,
   * or sends a malformed line ends the session: ended() turns true with
   * reason(); the run then finishes cleanly with what it has.
   *
   * A well-formed position the simulation must not follow (a device
   * glitch: farther than Limits::displacement from the first position, or
   * farther than Limits::jump from the last one followed) is answered with
   * "refused t x y z: why" instead of a force and not followed: the tool
   * keeps its last good target and the session goes on (the count is in
   * report()).
   */
  class LiveLink
  {
  public:
    struct Sample
    {
      double              time;
      std::vector<double> position;
    };

    /// What a client may ask (length units): how far from its first
    /// position, and how far from the last position followed.
    struct Limits
    {
      double displacement;
      double jump;
    };

    /**
     * What the communication thread answers with, in the tool's
     * coordinates (dim entries, dim x dim for the stiffness, row-major):
     * f(t, x) = force + stiffness (x - position) + rate (t - time) while
     * holding, 0 otherwise.
     */
    struct ForceModel
    {
      bool                valid   = false;
      bool                holding = false;
      double              time    = 0;
      std::vector<double> force, position, stiffness, rate;
    };

    /// Listens on 127.0.0.1:@p port (0: any free port) and writes the
    /// port number to @p port_file (complete, then renamed into place) so
    /// that a client can find it; starts the communication thread on
    /// process 0. @p period is the device's period (1 / 'Haptic rate'),
    /// against which answer latencies are reported. With
    /// @p reserve_core, process 0 simulates with one thread fewer while
    /// the link lives, if it would otherwise use every core, so that the
    /// communication thread answers without waiting for a core. Throws
    /// InputError if it cannot listen.
    LiveLink(int                port,
             double             timeout,
             unsigned int       dim,
             double             period,
             const Limits      &limits,
             const std::string &port_file,
             bool               reserve_core = true);
    ~LiveLink();

    /// Blocks until at least one position arrived (accepting the client
    /// first if need be) or the session ended; collective.
    std::vector<Sample>
    receive();

    /// The model later answers use (process 0; others ignore it); its
    /// positions are displacements from the first position received, as
    /// GraspTool::displacement() gives them.
    void
    set_model(const ForceModel &model);

    /// Whether a simulation step runs now (for the report of answers sent
    /// during steps).
    void
    set_stepping(const bool stepping)
    {
      step_running = stepping;
    }

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

    /// Positions received and answered so far (process 0's counts, shared
    /// by receive()).
    unsigned int samples = 0;

    /// What the device saw (process 0), for the end of the run: answers,
    /// latency median, 99th percentile and largest (from reading a
    /// position to sending its answer, ms), share within one period,
    /// answers sent while a step ran, and the lag of the simulated time
    /// behind the client's latest time when the client stopped (or, while
    /// it goes on, of @p simulated_time).
    std::string
    report(const double simulated_time) const;

    /// The latency of the last (at most 1000) answers, from reading a
    /// position to sending its force: median and 99th percentile (ms);
    /// empty before the first answer (process 0).
    std::vector<double>
    recent_latency() const;

  private:
    /// Why @p sample must not be followed (empty: it may); sets the
    /// origin from the first position.
    std::string
    refusal(const Sample &sample);

    /// Sends @p line and a newline to the client; false if it could not
    /// (the client stopped reading).
    bool
    send_line(const std::string &line);

    double timeout;
    /// The thread limit to restore when the link ends (0: unchanged).
    unsigned int restored_threads = 0;
    unsigned int dim;
    double       period;
    Limits       limits;
    /// The last position followed (communication thread).
    std::vector<double> last_followed;
    int                 listener = -1, client = -1;
    std::string         pending; // bytes of an incomplete line
    bool                has_ended = false;
    std::string         end_reason;

    // Shared between the communication thread and the simulation.
    mutable std::mutex      lock;
    std::condition_variable arrived;
    std::deque<Sample>      queue;
    ForceModel              model;
    std::string             thread_end; ///< why the thread stopped
    bool                    thread_done = false;
    std::atomic<bool>       stop{false}, step_running{false};
    std::vector<double>     latencies; ///< seconds, one per answer
    unsigned int            during_steps = 0;
    unsigned int            refused      = 0;
    std::string             first_refusal;
    double                  latest_client_time = 0;
    double                  lag_at_end         = 0;
    std::vector<double>     origin;
    std::thread             worker;

    /// The communication thread: accept, then read, answer and queue
    /// positions until the session ends or stop is set.
    void
    serve();
    /// Parses complete lines of pending; returns false with @p reason
    /// when the session ends.
    bool
    answer_lines(std::string &reason);
    /// The answer to a position at @p time under the current model (the
    /// position has passed refusal(), which set the origin).
    std::vector<double>
    force_at(const double time, const std::vector<double> &position);
    /// Waits up to the timeout for @p fd to be readable, in slices, so
    /// that stop is seen; false on timeout or stop.
    bool
    wait_readable(const int fd);
    void
    close_client();
  };
} // namespace tissuefem::tool
