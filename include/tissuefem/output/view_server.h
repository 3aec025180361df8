#pragma once

#include <memory>
#include <string>
#include <vector>

namespace tissuefem::output
{
  /**
   * The web server of the live view (process 0 only): HTTP for the page's
   * own files and WebSocket for the simulation's frames, on one port, run
   * by one thread of its own beside the simulation and the haptic thread
   * (Boost.Beast, header-only, from the Boost deal.II uses).
   *
   * What it serves is a fixed list: the page (index.html, view.js,
   * view.css from @p web_directory) and three.js with its orbit controls
   * from Debian's libjs-three. Every other path is answered 404, whatever
   * it contains, so no request names a file of its choosing. Requests are
   * read with limits (header 8 kB, no body, 10 s to arrive); a malformed,
   * oversized or slow request is answered 400 (or the connection closed)
   * and logged. WebSocket messages from a page are text commands of at
   * most 1 kB (longer ones close that page's connection, with a log line);
   * at most 256 wait for the run; at most 64 connections are open at once.
   * A browser may connect only from this server's own page (its Origin
   * header), not from another site open in the same browser.
   *
   * The simulation never waits for a page: it hands over the newest frame
   * (set_frame(), a shared buffer), and the server sends each page the
   * newest frame it has not yet seen, at most 'frame rate' times per
   * second, and only when that page's previous message has gone out, so a
   * slow page skips frames instead of queueing them. The topology (and a
   * new one after a mesh change) and text messages are queued per page;
   * a page whose queue exceeds 64 messages stops reading and is dropped.
   *
   * One page drives (the first connected that is still open; when it
   * closes the next one oldest takes over), the others watch: commands
   * from watchers are refused with a message to that page. When the
   * driving page leaves, a 'release' command lets go of what it held.
   */
  class ViewServer
  {
  public:
    struct Settings
    {
      /// Address to bind (127.0.0.1 unless the user names another).
      std::string address = "127.0.0.1";
      /// 0: any free port.
      int port = 0;
      /// Where index.html, view.js and view.css are.
      std::string web_directory;
      /// Where Debian's libjs-three put three.js (/usr/share/javascript/three).
      std::string three_directory;
      /// At most this many frames per second to each page.
      double frame_rate = 60;
    };

    /// A command from the driving page (one text message).
    struct Command
    {
      unsigned int page;
      std::string  text;
    };

    /// Binds and starts the server's thread. Throws InputError (naming
    /// 'Output/Live view') if a file to serve is missing or the address
    /// cannot be bound.
    explicit ViewServer(const Settings &settings);
    /// close(), if not yet done.
    ~ViewServer();

    ViewServer(const ViewServer &) = delete;
    ViewServer &
    operator=(const ViewServer &)
      = delete;

    /// The port listened on.
    unsigned short
    port() const;

    /// The text message every page gets first (the scene's description).
    void
    set_greeting(const std::string &text);

    /// The binary topology message, sent now to every page and to every
    /// page that connects later.
    void
    set_topology(std::shared_ptr<const std::string> bytes);

    /// The newest binary frame (older ones not yet sent are skipped).
    void
    set_frame(std::shared_ptr<const std::string> bytes);

    /// A text message to every page now.
    void
    broadcast(const std::string &text);

    /// A text message to page @p page only.
    void
    send_to(const unsigned int page, const std::string &text);

    /// The commands received from the driving page since the last call.
    std::vector<Command>
    take_commands();

    /// Waits up to @p seconds for a command or for the last page to close;
    /// returns at once if there are commands.
    void
    wait(const double seconds);

    /// Pages connected now.
    unsigned int
    pages() const;

    /// Lines for the run's log since the last call (refused requests,
    /// pages connecting and leaving).
    std::vector<std::string>
    take_log();

    /// The last text message pages get before the connections close.
    void
    finish(const std::string &text);

    /// Sends every page the message of finish(), closes the connections
    /// (waiting at most 1 s for pages to take what is queued) and stops
    /// the thread; the log stays readable.
    void
    close();

    struct Impl;

  private:
    std::unique_ptr<Impl> impl;
  };

  /// The first @p length bytes of @p text that form whole UTF-8 characters,
  /// other bytes replaced by '?' (for text sent to a browser).
  std::string
  printable(const std::string &text, const std::size_t length);

  /// @p text as a JSON string literal (quoted, with escapes; bytes that are
  /// not UTF-8 become '?').
  std::string
  json_quote(const std::string &text);
} // namespace tissuefem::output
