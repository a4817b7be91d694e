#include "view/server.h"

#include <algorithm>
#include <atomic>
#include <optional>
#include <deque>
#include <thread>
#include <vector>

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include "strata/core/error.h"

namespace strata::view {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;

constexpr auto kHeaderTimeout = std::chrono::seconds(15);

// "http://host:port" -> "host:port"; "" when the origin has no scheme.
std::string originHost(beast::string_view origin) {
  const auto pos = origin.find("://");
  if (pos == beast::string_view::npos) return {};
  return std::string(origin.substr(pos + 3));
}

}  // namespace

struct Server::Impl {
  Scene& scene;
  ServerOptions options;
  RequestHandler handler;
  // Before the io_context: the sessions its pending handlers hold at destruction still count.
  std::atomic<int> clients{0};
  std::atomic<std::uint64_t> sessions_total{0}, messages_sent{0}, bytes_sent{0}, requests{0},
      refused{0};
  class WsSession;
  std::vector<std::weak_ptr<WsSession>> sessions;  // server thread only

  asio::io_context ioc{1};
  tcp::acceptor acceptor{ioc};
  std::thread thread;
  std::atomic<bool> running{false};
  std::uint16_t bound_port = 0;

  Impl(Scene& s, ServerOptions o, RequestHandler h)
      : scene(s), options(std::move(o)), handler(std::move(h)) {}

  void accept();
  void onHttp(tcp::socket socket);
  void wakeSessions();
};

// One WebSocket client: sends the scene's changes, one message in flight at a time, and answers
// its requests. Lives on the server's thread only.
class Server::Impl::WsSession : public std::enable_shared_from_this<WsSession> {
 public:
  WsSession(Impl& server, beast::tcp_stream stream) : server_(server), ws_(std::move(stream)) {}
  ~WsSession() { --server_.clients; }

  void start(http::request<http::string_body> request) {
    ++server_.clients;
    ++server_.sessions_total;
    beast::get_lowest_layer(ws_).expires_never();
    // A peer that stops answering (no pong in 30 s, no reply to a close in 5 s) is dropped.
    websocket::stream_base::timeout timeouts{};
    timeouts.handshake_timeout = std::chrono::seconds(5);
    timeouts.idle_timeout = std::chrono::seconds(30);
    timeouts.keep_alive_pings = true;
    ws_.set_option(timeouts);
    ws_.read_message_max(server_.options.max_request_bytes);
    ws_.async_accept(request, [self = shared_from_this()](beast::error_code ec) {
      if (ec) return;
      self->open_ = true;
      self->read();
      self->pump();
    });
  }

  // Sends what is due: an answer first, then the scene's changes since this client's version.
  void pump() {
    if (!open_ || writing_) return;
    Message next;
    if (!answers_.empty()) {
      next = std::move(answers_.front());
      answers_.pop_front();
    } else {
      if (pending_.empty()) {
        std::vector<Message> changed;
        version_ = server_.scene.changesSince(version_, &changed);
        pending_.assign(changed.begin(), changed.end());
      }
      if (pending_.empty() && synced_) return;
      if (pending_.empty()) {
        // Everything the scene held when the client came has been sent: the page frames it.
        next = encodeMessage({{"type", "synced"}, {"version", version_}});
        synced_ = true;
      } else {
        next = std::move(pending_.front());
        pending_.pop_front();
      }
    }
    writing_ = true;
    ws_.binary(true);
    ws_.async_write(asio::buffer(*next),
                    [self = shared_from_this(), next](beast::error_code ec, std::size_t n) {
                      self->writing_ = false;
                      if (ec) {
                        self->open_ = false;
                        return;
                      }
                      ++self->server_.messages_sent;
                      self->server_.bytes_sent += n;
                      self->pump();
                    });
  }

  void close() {
    if (!open_) return;
    open_ = false;
    beast::error_code ec;
    beast::get_lowest_layer(ws_).socket().shutdown(tcp::socket::shutdown_both, ec);
    beast::get_lowest_layer(ws_).socket().close(ec);
  }

 private:
  void read() {
    ws_.async_read(buffer_, [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (ec) {
        // Closed, a protocol error or a message over the limit: the session ends.
        if (ec != websocket::error::closed) ++self->server_.refused;
        self->open_ = false;
        return;
      }
      self->answer();
      self->read();
    });
  }

  void answer() {
    const std::string text = beast::buffers_to_string(buffer_.data());
    buffer_.consume(buffer_.size());
    ++server_.requests;
    Message reply;
    const nlohmann::json request = nlohmann::json::parse(text, nullptr, false);
    if (request.is_discarded() || !request.is_object()) {
      ++server_.refused;
      reply = encodeMessage({{"type", "error"}, {"message", "request is not a JSON object"}});
    } else if (static_cast<int>(answers_.size()) >= server_.options.max_pending_answers) {
      ++server_.refused;  // a client that asks faster than it reads: dropped, counted
    } else if (server_.handler) {
      try {
        reply = server_.handler(request);
      } catch (const std::exception& e) {
        reply = encodeMessage({{"type", "error"}, {"message", e.what()}});
      }
    }
    if (reply) answers_.push_back(std::move(reply));
    pump();
  }

  Impl& server_;
  websocket::stream<beast::tcp_stream> ws_;
  beast::flat_buffer buffer_;
  std::deque<Message> pending_;
  std::deque<Message> answers_;
  std::uint64_t version_ = 0;
  bool writing_ = false;
  bool open_ = false;
  bool synced_ = false;
};

namespace {

// One HTTP connection: static files, or the upgrade to a WebSocket session.
class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  using Upgrade = std::function<void(beast::tcp_stream, http::request<http::string_body>)>;
  HttpSession(tcp::socket socket, const ServerOptions& options, std::atomic<std::uint64_t>& refused,
              std::function<bool()> full, Upgrade upgrade)
      : stream_(std::move(socket)), options_(options), refused_(refused), full_(std::move(full)),
        upgrade_(std::move(upgrade)) {}

  void read() {
    parser_.emplace();
    parser_->body_limit(options_.max_request_bytes);
    parser_->header_limit(16 * 1024);
    stream_.expires_after(kHeaderTimeout);
    http::async_read(stream_, buffer_, *parser_,
                     [self = shared_from_this()](beast::error_code ec, std::size_t) {
                       self->onRead(ec);
                     });
  }

 private:
  void onRead(beast::error_code ec) {
    if (ec == http::error::end_of_stream) return close();
    if (ec) {
      // Malformed or oversized request, or a client too slow to send its headers.
      ++refused_;
      if (ec != beast::error::timeout) return reply(http::status::bad_request, "bad request\n", false);
      return close();
    }
    http::request<http::string_body> request = parser_->release();
    if (websocket::is_upgrade(request)) {
      if (request.target() != "/ws") {
        ++refused_;
        return reply(http::status::not_found, "no WebSocket here: /ws\n", false);
      }
      const auto origin = request.find(http::field::origin);
      if (origin != request.end() && originHost(origin->value()) != std::string(request[http::field::host])) {
        ++refused_;
        return reply(http::status::forbidden, "WebSocket from another origin refused\n", false);
      }
      if (full_()) {
        ++refused_;
        return reply(http::status::service_unavailable, "too many clients\n", false);
      }
      stream_.expires_never();
      return upgrade_(std::move(stream_), std::move(request));
    }
    if (request.method() != http::verb::get && request.method() != http::verb::head) {
      ++refused_;
      return reply(http::status::method_not_allowed, "only GET and HEAD\n", request.keep_alive());
    }
    std::string path(request.target());
    path = path.substr(0, path.find('?'));
    const StaticFile* file = findStaticFile(path);
    if (!file) return reply(http::status::not_found, "not found\n", request.keep_alive());
    auto response = std::make_shared<http::response<http::string_body>>(http::status::ok, request.version());
    response->set(http::field::server, "strata-view");
    response->set(http::field::content_type, file->mime);
    response->set(http::field::cache_control, "no-cache");
    response->set("X-Content-Type-Options", "nosniff");
    response->keep_alive(request.keep_alive());
    if (request.method() == http::verb::get) {
      response->body().assign(reinterpret_cast<const char*>(file->data), file->size);
      response->prepare_payload();
    } else {
      response->content_length(file->size);
    }
    write(response);
  }

  void reply(http::status status, const std::string& text, bool keep_alive) {
    auto response = std::make_shared<http::response<http::string_body>>(status, 11);
    response->set(http::field::server, "strata-view");
    response->set(http::field::content_type, "text/plain");
    response->keep_alive(keep_alive);
    response->body() = text;
    response->prepare_payload();
    write(response);
  }

  void write(const std::shared_ptr<http::response<http::string_body>>& response) {
    http::async_write(stream_, *response,
                      [self = shared_from_this(), response](beast::error_code ec, std::size_t) {
                        if (ec || !response->keep_alive()) return self->close();
                        self->read();
                      });
  }

  void close() {
    beast::error_code ec;
    stream_.socket().shutdown(tcp::socket::shutdown_send, ec);
  }

  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  const ServerOptions& options_;
  std::atomic<std::uint64_t>& refused_;
  std::function<bool()> full_;
  Upgrade upgrade_;
};

}  // namespace

void Server::Impl::accept() {
  acceptor.async_accept([this](beast::error_code ec, tcp::socket socket) {
    if (ec) {
      if (ec == asio::error::operation_aborted) return;
    } else {
      onHttp(std::move(socket));
    }
    accept();
  });
}

void Server::Impl::onHttp(tcp::socket socket) {
  auto full = [this] { return clients.load() >= options.max_clients; };
  auto upgrade = [this](beast::tcp_stream stream, http::request<http::string_body> request) {
    auto session = std::make_shared<WsSession>(*this, std::move(stream));
    sessions.erase(std::remove_if(sessions.begin(), sessions.end(),
                                  [](const std::weak_ptr<WsSession>& s) { return s.expired(); }),
                   sessions.end());
    sessions.push_back(session);
    session->start(std::move(request));
  };
  std::make_shared<HttpSession>(std::move(socket), options, refused, full, upgrade)->read();
}

void Server::Impl::wakeSessions() {
  for (const auto& weak : sessions) {
    if (auto s = weak.lock()) s->pump();
  }
}

Server::Server(Scene& scene, ServerOptions options, RequestHandler handler)
    : impl_(std::make_unique<Impl>(scene, std::move(options), std::move(handler))) {}

Server::~Server() {
  stop();
  impl_->scene.setChangeListener(nullptr);
}

void Server::start() {
  Impl& s = *impl_;
  if (s.running) return;
  beast::error_code ec;
  const auto address = asio::ip::make_address(s.options.bind_address, ec);
  if (ec) throw InputError("viewer: '" + s.options.bind_address + "' is not an IP address");
  const tcp::endpoint endpoint(address, s.options.port);
  s.acceptor.open(endpoint.protocol(), ec);
  if (!ec) s.acceptor.set_option(asio::socket_base::reuse_address(true), ec);
  if (!ec) s.acceptor.bind(endpoint, ec);
  if (!ec) s.acceptor.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) {
    throw InputError("viewer: cannot listen on " + s.options.bind_address + ":" +
                     std::to_string(s.options.port) + " (" + ec.message() + ")");
  }
  s.bound_port = s.acceptor.local_endpoint().port();
  s.scene.setChangeListener([&s] { asio::post(s.ioc, [&s] { s.wakeSessions(); }); });
  s.accept();
  s.running = true;
  s.thread = std::thread([&s] { s.ioc.run(); });
}

void Server::stop() {
  Impl& s = *impl_;
  if (!s.running.exchange(false)) return;
  asio::post(s.ioc, [&s] {
    beast::error_code ec;
    s.acceptor.close(ec);
    for (const auto& weak : s.sessions) {
      if (auto session = weak.lock()) session->close();
    }
    s.ioc.stop();
  });
  if (s.thread.joinable()) s.thread.join();
}

std::uint16_t Server::port() const { return impl_->bound_port; }

ServerStats Server::stats() const {
  const Impl& s = *impl_;
  ServerStats out;
  out.clients = s.clients.load();
  out.sessions_total = s.sessions_total.load();
  out.messages_sent = s.messages_sent.load();
  out.bytes_sent = s.bytes_sent.load();
  out.requests = s.requests.load();
  out.refused = s.refused.load();
  return out;
}

}  // namespace strata::view
