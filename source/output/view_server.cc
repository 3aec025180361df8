// The live view's HTTP and WebSocket server (Boost.Beast). Everything
// below runs on the server's one thread except the public functions, which
// post to it or touch only the mutex-guarded command queue and log.
#include <tissuefem/base/input_error.h>
#include <tissuefem/output/view_server.h>

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>

namespace tissuefem::output
{
  namespace beast     = boost::beast;
  namespace http      = beast::http;
  namespace websocket = beast::websocket;
  namespace net       = boost::asio;
  using tcp           = net::ip::tcp;

  std::string
  printable(const std::string &text, const std::size_t length)
  {
    // Whole UTF-8 characters only; any other byte becomes '?', so that a
    // text frame built from it is valid UTF-8 (browsers close on invalid).
    std::string out;
    for (std::size_t i = 0; i < text.size() && out.size() < length;)
      {
        const unsigned char c     = text[i];
        const std::size_t   n     = c < 0x80           ? 1
                                    : (c >> 5) == 0x6  ? 2
                                    : (c >> 4) == 0xe  ? 3
                                    : (c >> 3) == 0x1e ? 4
                                                       : 0;
        bool                whole = n > 0 && i + n <= text.size();
        for (std::size_t k = 1; whole && k < n; ++k)
          whole = (static_cast<unsigned char>(text[i + k]) >> 6) == 0x2;
        if (whole)
          out.append(text, i, n), i += n;
        else
          out += '?', ++i;
      }
    return out;
  }


  std::string
  json_quote(const std::string &raw)
  {
    const std::string text = printable(raw, raw.size());
    std::string       out  = "\"";
    for (const unsigned char c : text)
      if (c == '"' || c == '\\')
        out += std::string("\\") + char(c);
      else if (c == '\n')
        out += "\\n";
      else if (c < 0x20)
        {
          char code[8];
          std::snprintf(code, sizeof(code), "\\u%04x", c);
          out += code;
        }
      else
        out += char(c);
    return out + "\"";
  }

  namespace
  {
    /// Most pages at once, queued messages per page, a command's bytes.
    constexpr std::size_t max_pages = 16, max_queue = 64, max_command = 1024,
                          max_commands = 256, max_connections = 64;

    struct Message
    {
      bool                               binary;
      std::shared_ptr<const std::string> bytes;
    };

    std::string
    read_file(const std::string &name)
    {
      std::ifstream in(name, std::ios::binary);
      if (!in)
        throw InputError("Output/Live view: cannot read '" + name
                         + "', a file the page needs"
                         + (name.find("three") != std::string::npos
                              ? " (install Debian's libjs-three)"
                              : ""));
      std::ostringstream text;
      text << in.rdbuf();
      return text.str();
    }
  } // namespace

  class WsPage;

  namespace
  {
    /// Counts a connection in @p count for as long as it lives.
    class Counted
    {
    public:
      explicit Counted(std::atomic<unsigned int> &count)
          : count(count)
      {
        ++count;
      }
      ~Counted()
      {
        --count;
      }
      Counted(const Counted &) = delete;
      Counted &
      operator=(const Counted &)
        = delete;

    private:
      std::atomic<unsigned int> &count;
    };
  } // namespace

  struct ViewServer::Impl
  {
    Settings settings;
    /// Connections open now (HTTP sessions and pages), against
    /// max_connections; declared before the io_context, whose end ends the
    /// sessions that count here.
    std::atomic<unsigned int> connections{0};
    net::io_context           ioc{1};
    tcp::acceptor             acceptor{ioc};
    net::steady_timer         ticker{ioc}, deadline{ioc};
    /// Path -> (content, MIME type): the whole list of what is served.
    std::map<std::string, std::pair<std::string, std::string>> files;

    // Server thread only.
    std::map<unsigned int, std::shared_ptr<WsPage>> open_pages;
    unsigned int                                    next_id = 1;
    std::shared_ptr<const std::string>              greeting, topology, frame;
    unsigned long                                   frame_id = 0;
    bool                                            closing  = false;
    std::shared_ptr<const std::string>              farewell;

    // Shared with the simulation.
    std::mutex                lock;
    std::condition_variable   changed;
    std::deque<Command>       commands;
    std::vector<std::string>  log_lines;
    std::atomic<unsigned int> page_count{0};
    std::thread               thread;

    void
    log(const std::string &line)
    {
      std::lock_guard<std::mutex> guard(lock);
      if (log_lines.size() < 1000)
        log_lines.push_back(line);
    }

    /// Whether @p origin is this server's page: http://HOST:PORT with HOST
    /// the bound address, 127.0.0.1, localhost or [::1].
    bool
    own_origin(const beast::string_view origin) const
    {
      const std::string port
        = ":" + std::to_string(acceptor.local_endpoint().port());
      for (const std::string &host : {settings.address,
                                      std::string("127.0.0.1"),
                                      std::string("localhost"),
                                      std::string("[::1]")})
        if (origin == "http://" + host + port)
          return true;
      return false;
    }

    /// A copy of the open pages to loop over: sending may close a page
    /// (one that stopped reading), which takes it out of open_pages.
    std::map<unsigned int, std::shared_ptr<WsPage>>
    pages_now() const
    {
      return open_pages;
    }

    void
    accept();
    void
    tick();
    void
    add(const std::shared_ptr<WsPage> &page);
    void
    remove(const unsigned int id, const std::string &why);
    void
    command(const unsigned int id, const std::string &text);
    void
    announce_roles();
    void
    shutdown();
  };


  /// One WebSocket connection: a queue of messages going out, the newest
  /// frame offered when nothing else is going out.
  class WsPage : public std::enable_shared_from_this<WsPage>
  {
  public:
    WsPage(tcp::socket &&socket, ViewServer::Impl &server)
        : counted(server.connections)
        , ws(std::move(socket))
        , server(server)
    {
    }

    unsigned int id = 0;

    void
    accept(http::request<http::empty_body> request)
    {
      // Pings when idle: a page that only watches sends nothing, and must
      // not be taken for a dead one (Beast's idle timeout, 300 s).
      auto timeouts
        = websocket::stream_base::timeout::suggested(beast::role_type::server);
      timeouts.keep_alive_pings = true;
      ws.set_option(timeouts);
      ws.read_message_max(max_command);
      // A frame is one WebSocket frame, not pieces of 4 kB.
      ws.auto_fragment(false);
      ws.async_accept(request,
                      [self = shared_from_this()](beast::error_code ec) {
                        if (ec)
                          self->server.log("live view: WebSocket handshake "
                                           "refused: "
                                           + ec.message());
                        else
                          {
                            self->server.add(self);
                            self->read();
                          }
                      });
    }

    void
    send(const bool binary, std::shared_ptr<const std::string> bytes)
    {
      if (closed)
        return;
      if (queue.size() >= max_queue)
        {
          close("stopped reading (" + std::to_string(max_queue)
                + " messages waiting)");
          return;
        }
      queue.push_back({binary, std::move(bytes)});
      if (!writing)
        write_next();
    }

    /// Sends the newest frame if this page is idle and has not seen it.
    void
    offer(const unsigned long                       frame_id,
          const std::shared_ptr<const std::string> &frame)
    {
      if (closed || writing || !queue.empty() || frame_id <= sent_frame
          || !frame)
        return;
      sent_frame = frame_id;
      send(true, frame);
    }

    /// Closes after what is queued has gone out.
    void
    close_when_sent()
    {
      closing = true;
      if (!writing && queue.empty())
        start_close();
    }

    /// Closes now (the page misbehaved or stopped reading).
    void
    close(const std::string &why)
    {
      if (closed)
        return;
      closed = true;
      beast::error_code ignored;
      beast::get_lowest_layer(ws).socket().close(ignored);
      server.remove(id, why);
    }

  private:
    Counted                              counted;
    websocket::stream<beast::tcp_stream> ws;
    ViewServer::Impl                    &server;
    beast::flat_buffer                   in;
    std::deque<Message>                  queue;
    bool          writing = false, closing = false, closed = false;
    unsigned long sent_frame = 0;

    void
    read()
    {
      ws.async_read(in,
                    [self = shared_from_this()](beast::error_code ec,
                                                std::size_t) {
                      self->on_read(ec);
                    });
    }

    void
    on_read(const beast::error_code ec)
    {
      if (ec)
        {
          // A page closing normally is not worth a warning.
          const bool normal = ec == websocket::error::closed
                              || ec == net::error::eof
                              || ec == net::error::connection_reset
                              || ec == net::error::not_connected
                              || ec == net::error::operation_aborted;
          if (!closed)
            {
              closed = true;
              // Also the socket: a write may still wait on it.
              beast::error_code ignored;
              beast::get_lowest_layer(ws).socket().close(ignored);
              server.remove(id,
                            normal ? "closed"
                                   : "connection ended: " + ec.message());
            }
          return;
        }
      if (!ws.got_text())
        send(false,
             std::make_shared<const std::string>(
               "{\"type\":\"error\",\"message\":\"binary messages are not "
               "commands; send text\"}"));
      else
        server.command(id, beast::buffers_to_string(in.data()));
      in.consume(in.size());
      read();
    }

    void
    write_next()
    {
      writing          = true;
      const Message &m = queue.front();
      ws.binary(m.binary);
      ws.async_write(net::buffer(*m.bytes),
                     [self = shared_from_this(),
                      keep = m.bytes](beast::error_code ec, std::size_t) {
                       self->on_write(ec);
                     });
    }

    void
    on_write(const beast::error_code ec)
    {
      writing = false;
      if (ec)
        {
          close("could not send: " + ec.message());
          return;
        }
      queue.pop_front();
      if (!queue.empty())
        write_next();
      else if (closing)
        start_close();
    }

    void
    start_close()
    {
      ws.async_close(websocket::close_code::normal,
                     [self = shared_from_this()](beast::error_code) {
                       self->close("closed by the run");
                     });
    }
  };


  /// One HTTP connection: requests for the page's files, or the upgrade
  /// to a WebSocket.
  class HttpSession : public std::enable_shared_from_this<HttpSession>
  {
  public:
    HttpSession(tcp::socket &&socket, ViewServer::Impl &server)
        : counted(server.connections)
        , stream(std::move(socket))
        , server(server)
    {
    }

    void
    read()
    {
      parser.emplace();
      parser->header_limit(8 * 1024);
      parser->body_limit(0);
      stream.expires_after(std::chrono::seconds(10));
      http::async_read(stream,
                       buffer,
                       *parser,
                       [self = shared_from_this()](beast::error_code ec,
                                                   std::size_t) {
                         self->on_read(ec);
                       });
    }

  private:
    Counted                                               counted;
    beast::tcp_stream                                     stream;
    ViewServer::Impl                                     &server;
    beast::flat_buffer                                    buffer{16 * 1024};
    std::optional<http::request_parser<http::empty_body>> parser;

    void
    on_read(const beast::error_code ec)
    {
      if (ec == http::error::end_of_stream || ec == net::error::eof
          || ec == beast::error::timeout || ec == net::error::operation_aborted)
        return close();
      if (ec)
        {
          server.log("live view: malformed HTTP request refused: "
                     + ec.message());
          return respond(http::status::bad_request,
                         "malformed request: " + ec.message() + "\n",
                         "text/plain",
                         false);
        }
      http::request<http::empty_body> request = parser->release();
      if (websocket::is_upgrade(request))
        {
          if (request.target() != "/ws")
            return respond(http::status::not_found,
                           "no WebSocket here; use /ws\n",
                           "text/plain",
                           false);
          // A browser names the page that opens the connection: only this
          // server's own page may watch and drive the run (another web page
          // open in the same browser may not; clients that are not
          // browsers send no Origin).
          const auto origin = request.find(http::field::origin);
          if (origin != request.end() && !server.own_origin(origin->value()))
            {
              server.log("live view: WebSocket from another site refused: "
                         + printable(std::string(origin->value()), 100));
              return respond(http::status::forbidden,
                             "only this server's page may connect\n",
                             "text/plain",
                             false);
            }
          if (server.open_pages.size() >= max_pages || server.closing)
            return respond(http::status::service_unavailable,
                           "too many pages\n",
                           "text/plain",
                           false);
          std::make_shared<WsPage>(stream.release_socket(), server)
            ->accept(std::move(request));
          return;
        }
      if (request.method() != http::verb::get
          && request.method() != http::verb::head)
        return respond(http::status::method_not_allowed,
                       "only GET\n",
                       "text/plain",
                       request.keep_alive());
      std::string target(request.target());
      target          = target.substr(0, target.find('?'));
      const auto file = server.files.find(target);
      if (file == server.files.end())
        {
          server.log("live view: no such page file: " + target.substr(0, 200));
          return respond(http::status::not_found,
                         "not found\n",
                         "text/plain",
                         request.keep_alive());
        }
      respond(http::status::ok,
              request.method() == http::verb::head ? "" : file->second.first,
              file->second.second,
              request.keep_alive());
    }

    void
    respond(const http::status status,
            const std::string &body,
            const std::string &type,
            const bool         keep_alive)
    {
      auto response
        = std::make_shared<http::response<http::string_body>>(status, 11);
      response->set(http::field::server, "tissuefem");
      response->set(http::field::content_type, type);
      response->set(http::field::cache_control, "no-store");
      response->keep_alive(keep_alive);
      response->body() = body;
      response->prepare_payload();
      http::async_write(stream,
                        *response,
                        [self = shared_from_this(),
                         response](beast::error_code ec, std::size_t) {
                          if (ec || !response->keep_alive())
                            return self->close();
                          self->read();
                        });
    }

    void
    close()
    {
      beast::error_code ignored;
      stream.socket().shutdown(tcp::socket::shutdown_send, ignored);
      stream.close();
    }
  };


  void
  ViewServer::Impl::accept()
  {
    acceptor.async_accept([this](beast::error_code ec, tcp::socket socket) {
      if (ec)
        {
          if (!acceptor.is_open())
            return;
          // Out of file descriptors, say: try again a little later instead
          // of spinning.
          log("live view: accept failed: " + ec.message());
          deadline.expires_after(std::chrono::milliseconds(100));
          deadline.async_wait([this](beast::error_code e) {
            if (!e)
              accept();
          });
          return;
        }
      if (connections >= max_connections)
        {
          // Too many at once: this one is closed unanswered.
          log("live view: connection refused: "
              + std::to_string(max_connections) + " already open");
          beast::error_code ignored;
          socket.close(ignored);
        }
      else
        std::make_shared<HttpSession>(std::move(socket), *this)->read();
      accept();
    });
  }


  void
  ViewServer::Impl::tick()
  {
    for (const auto &[id, page] : pages_now())
      page->offer(frame_id, frame);
    ticker.expires_after(
      std::chrono::microseconds(long(1e6 / settings.frame_rate)));
    ticker.async_wait([this](beast::error_code ec) {
      if (!ec)
        tick();
    });
  }


  void
  ViewServer::Impl::add(const std::shared_ptr<WsPage> &page)
  {
    if (closing)
      {
        page->close_when_sent();
        return;
      }
    page->id = next_id++;
    {
      std::lock_guard<std::mutex> guard(lock);
      open_pages[page->id] = page;
      page_count           = open_pages.size();
    }
    log("live view: page " + std::to_string(page->id) + " connected");
    if (greeting)
      page->send(false, greeting);
    if (topology)
      page->send(true, topology);
    announce_roles();
    changed.notify_all();
  }


  void
  ViewServer::Impl::remove(const unsigned int id, const std::string &why)
  {
    const bool drove = !open_pages.empty() && open_pages.begin()->first == id;
    {
      std::lock_guard<std::mutex> guard(lock);
      if (open_pages.erase(id) == 0)
        return;
      page_count = open_pages.size();
      // What the driving page held, it lets go of when it leaves.
      if (drove && !closing)
        commands.push_back({id, "release"});
    }
    log("live view: page " + std::to_string(id) + " " + why);
    announce_roles();
    changed.notify_all();
    if (closing && open_pages.empty())
      ioc.stop();
  }


  void
  ViewServer::Impl::announce_roles()
  {
    const auto pages = pages_now();
    if (closing || pages.empty())
      return;
    const unsigned int driver = pages.begin()->first;
    for (const auto &[id, page] : pages)
      page->send(false,
                 std::make_shared<const std::string>(
                   std::string("{\"type\":\"role\",\"page\":")
                   + std::to_string(id)
                   + ",\"drives\":" + (id == driver ? "true" : "false") + "}"));
  }


  void
  ViewServer::Impl::command(const unsigned int id, const std::string &text)
  {
    const auto page = open_pages.find(id);
    if (page == open_pages.end())
      return;
    if (page != open_pages.begin())
      {
        page->second->send(
          false,
          std::make_shared<const std::string>(
            "{\"type\":\"error\",\"message\":\"another page drives this run; "
            "this one watches\"}"));
        return;
      }
    bool full;
    {
      std::lock_guard<std::mutex> guard(lock);
      full = commands.size() >= max_commands;
      if (!full)
        commands.push_back({id, text});
    }
    changed.notify_all();
    // (Outside the lock: sending may close the page, which takes it.)
    if (full)
      page->second->send(false,
                         std::make_shared<const std::string>(
                           "{\"type\":\"error\",\"message\":\"too many "
                           "commands waiting for the run; this one was "
                           "dropped\"}"));
  }


  void
  ViewServer::Impl::shutdown()
  {
    closing = true;
    beast::error_code ignored;
    acceptor.close(ignored);
    ticker.cancel();
    if (open_pages.empty())
      return ioc.stop();
    const auto pages = pages_now();
    for (const auto &[id, page] : pages)
      {
        if (farewell)
          page->send(false, farewell);
        page->close_when_sent();
      }
    deadline.expires_after(std::chrono::seconds(1));
    deadline.async_wait([this](beast::error_code ec) {
      if (!ec)
        ioc.stop();
    });
  }


  ViewServer::ViewServer(const Settings &settings)
      : impl(std::make_unique<Impl>())
  {
    impl->settings          = settings;
    const std::string web   = settings.web_directory + "/",
                      three = settings.three_directory + "/";
    impl->files["/"]        = {read_file(web + "index.html"), "text/html"};
    impl->files["/view.js"]
      = {read_file(web + "view.js"), "application/javascript"};
    impl->files["/view.css"] = {read_file(web + "view.css"), "text/css"};
    impl->files["/three.min.js"]
      = {read_file(three + "build/three.min.js"), "application/javascript"};
    impl->files["/OrbitControls.js"]
      = {read_file(three + "examples/js/controls/OrbitControls.js"),
         "application/javascript"};
    impl->files["/index.html"] = impl->files["/"];

    beast::error_code ec;
    const auto        address = net::ip::make_address(settings.address, ec);
    if (ec)
      throw InputError("Output/Live view/Address: '" + settings.address
                       + "' is not an IP address");
    const tcp::endpoint endpoint(address,
                                 static_cast<unsigned short>(settings.port));
    impl->acceptor.open(endpoint.protocol(), ec);
    if (!ec)
      impl->acceptor.set_option(net::socket_base::reuse_address(true), ec);
    if (!ec)
      impl->acceptor.bind(endpoint, ec);
    if (!ec)
      impl->acceptor.listen(net::socket_base::max_listen_connections, ec);
    if (ec)
      throw InputError("Output/Live view/Port: cannot listen on "
                       + settings.address + ":" + std::to_string(settings.port)
                       + ": " + ec.message());
    impl->accept();
    impl->tick();
    impl->thread = std::thread([this]() {
      for (;;)
        try
          {
            impl->ioc.run();
            return;
          }
        catch (const std::exception &e)
          {
            // One connection's failure must not end the run or the view.
            impl->log(std::string("live view: ") + e.what());
          }
    });
  }


  ViewServer::~ViewServer()
  {
    close();
  }


  void
  ViewServer::close()
  {
    if (!impl->thread.joinable())
      return;
    net::post(impl->ioc, [this]() { impl->shutdown(); });
    impl->thread.join();
  }


  unsigned short
  ViewServer::port() const
  {
    return impl->acceptor.local_endpoint().port();
  }


  void
  ViewServer::set_greeting(const std::string &text)
  {
    auto bytes = std::make_shared<const std::string>(text);
    net::post(impl->ioc, [this, bytes]() { impl->greeting = bytes; });
  }


  void
  ViewServer::set_topology(std::shared_ptr<const std::string> bytes)
  {
    net::post(impl->ioc, [this, bytes]() {
      impl->topology = bytes;
      // A frame of the old mesh must not follow the new topology.
      impl->frame.reset();
      for (const auto &[id, page] : impl->pages_now())
        page->send(true, bytes);
    });
  }


  void
  ViewServer::set_frame(std::shared_ptr<const std::string> bytes)
  {
    net::post(impl->ioc, [this, bytes]() {
      impl->frame = bytes;
      ++impl->frame_id;
    });
  }


  void
  ViewServer::broadcast(const std::string &text)
  {
    auto bytes = std::make_shared<const std::string>(text);
    net::post(impl->ioc, [this, bytes]() {
      for (const auto &[id, page] : impl->pages_now())
        page->send(false, bytes);
    });
  }


  void
  ViewServer::send_to(const unsigned int page, const std::string &text)
  {
    auto bytes = std::make_shared<const std::string>(text);
    net::post(impl->ioc, [this, bytes, page]() {
      const auto p = impl->open_pages.find(page);
      if (p != impl->open_pages.end())
        p->second->send(false, bytes);
    });
  }


  std::vector<ViewServer::Command>
  ViewServer::take_commands()
  {
    std::lock_guard<std::mutex> guard(impl->lock);
    std::vector<Command> result(impl->commands.begin(), impl->commands.end());
    impl->commands.clear();
    return result;
  }


  void
  ViewServer::wait(const double seconds)
  {
    std::unique_lock<std::mutex> guard(impl->lock);
    impl->changed.wait_for(guard,
                           std::chrono::duration<double>(seconds),
                           [this]() {
                             return !impl->commands.empty()
                                    || impl->page_count == 0;
                           });
  }


  unsigned int
  ViewServer::pages() const
  {
    return impl->page_count;
  }


  std::vector<std::string>
  ViewServer::take_log()
  {
    std::lock_guard<std::mutex> guard(impl->lock);
    std::vector<std::string>    result;
    result.swap(impl->log_lines);
    return result;
  }


  void
  ViewServer::finish(const std::string &text)
  {
    auto bytes = std::make_shared<const std::string>(text);
    net::post(impl->ioc, [this, bytes]() { impl->farewell = bytes; });
  }
} // namespace tissuefem::output
