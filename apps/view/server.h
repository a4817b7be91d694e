#pragma once
// The viewer's server: HTTP for the page's own files (compiled into the program: nothing is read
// from disk, so no request can reach another file) and a WebSocket at /ws that streams the Scene's
// changes to every client. Built on Boost.Beast (Debian's Boost 1.74, header-only): one library for
// both protocols on one port, so the page's socket is same-origin.
//
// Each client's session sends the scene as it stands when it connects, then a "synced" message
// (the page frames the scene then), then what changed; a slow
// client gets each item's latest message when it is ready, never a growing queue (Scene). Clients
// may send text JSON requests ({"type": "query", ...}); the RequestHandler answers them on the
// server's thread, one at a time.
//
// Security: binds 127.0.0.1 unless told otherwise; a WebSocket whose Origin is not the page's own
// host is refused (403); requests over 64 KiB, slow headers (15 s) and more than max_clients
// sockets are refused; only GET and HEAD.
//
// Threads: start() runs the server on a thread of its own; Scene changes from any thread wake the
// sessions. stop() (and the destructor) closes every connection and joins that thread.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "view/scene.h"

namespace strata::view {

struct ServerOptions {
  /// Address to listen on: loopback by default; "0.0.0.0" exposes the view to the network.
  std::string bind_address = "127.0.0.1";
  /// TCP port; 0 picks a free one (port() says which).
  std::uint16_t port = 8765;
  /// Largest HTTP request or WebSocket message accepted from a client.
  std::size_t max_request_bytes = 64 * 1024;
  /// Open WebSocket sessions beyond this are refused (503).
  int max_clients = 64;
  /// Requests waiting for an answer per client; more are answered with an error message.
  int max_pending_answers = 16;
};

/// Answers one client request (a JSON object) with a message for that client, or null for none.
/// Runs on the server's thread. An exception it throws becomes an "error" message to the client.
using RequestHandler = std::function<Message(const nlohmann::json& request)>;

struct ServerStats {
  int clients = 0;                  // open WebSocket sessions
  std::uint64_t sessions_total = 0; // sessions ever accepted
  std::uint64_t messages_sent = 0;
  std::uint64_t bytes_sent = 0;
  std::uint64_t requests = 0;       // client requests handled
  std::uint64_t refused = 0;        // bad HTTP, bad origin, too many clients, bad requests
};

class Server {
 public:
  Server(Scene& scene, ServerOptions options, RequestHandler handler = nullptr);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  /// Binds and starts serving on a thread of its own. InputError naming the address when it cannot
  /// be bound (in use, not an address of this machine).
  void start();
  /// Closes every connection and joins the server's thread. Idempotent.
  void stop();
  /// The port bound (after start()).
  std::uint16_t port() const;
  ServerStats stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The page's files compiled into the program: path ("/index.html") -> content and MIME type.
struct StaticFile {
  const unsigned char* data;
  std::size_t size;
  const char* mime;
};
/// The file served at `path` ("/" is "/index.html"), null when the bundle has none.
const StaticFile* findStaticFile(const std::string& path);

}  // namespace strata::view
