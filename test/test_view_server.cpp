// The viewer's server alone (apps/view/server.h), with Boost.Beast clients on 127.0.0.1: the page's
// own files and nothing else, malformed and hostile requests, the WebSocket stream (the scene, then
// "synced", then changes), a slow client that gets the latest state instead of every update, many
// clients, a client gone mid-stream, another origin, too many clients, requests and their answers.
// (What `strata view` serves and its bad input: test_view_offline.cpp.)
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstring>
#include <thread>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/read.hpp>
#include <boost/asio/write.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include "strata/core/error.h"
#include "view/scene.h"
#include "view/server.h"
#include "view/wire.h"

namespace strata::view {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;

Message item(const std::string& id, int value, std::size_t payload_floats = 0) {
  std::vector<float> payload(payload_floats, static_cast<float>(value));
  return encodeMessage({{"type", "stats"}, {"id", id}, {"value", value}},
                       {{"values", WireArray::Type::kF32, payload.data(), payload.size()}});
}

struct Served {
  Scene scene;
  std::unique_ptr<Server> server;
  explicit Served(ServerOptions options = {}, RequestHandler handler = nullptr) {
    options.port = 0;
    server = std::make_unique<Server>(scene, options, std::move(handler));
    server->start();
  }
  std::string host() const { return "127.0.0.1:" + std::to_string(server->port()); }
};

// One HTTP exchange; the raw request text is sent as it is (so malformed ones can be).
std::string rawHttp(std::uint16_t port, const std::string& request) {
  asio::io_context ioc;
  tcp::socket socket(ioc);
  socket.connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port));
  asio::write(socket, asio::buffer(request));
  std::string response;
  beast::error_code ec;
  std::array<char, 4096> chunk{};
  for (;;) {
    const std::size_t n = socket.read_some(asio::buffer(chunk), ec);
    response.append(chunk.data(), n);
    if (ec) break;
    if (response.find("\r\n\r\n") != std::string::npos) {
      // Enough for a status line and headers; read the body when it is announced.
      const auto cl = response.find("Content-Length: ");
      if (cl == std::string::npos) break;
      const std::size_t length = std::stoul(response.substr(cl + 16));
      if (response.size() >= response.find("\r\n\r\n") + 4 + length) break;
    }
  }
  return response;
}

int statusOf(const std::string& response) {
  return response.size() > 12 ? std::stoi(response.substr(9, 3)) : 0;
}

class WsClient {
 public:
  explicit WsClient(std::uint16_t port, const std::string& origin = "") : ws_(ioc_) {
    ws_.next_layer().connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port));
    const std::string host = "127.0.0.1:" + std::to_string(port);
    if (!origin.empty()) {
      ws_.set_option(websocket::stream_base::decorator(
          [origin](websocket::request_type& r) { r.set(http::field::origin, origin); }));
    }
    ws_.read_message_max(64u << 20);
    ws_.handshake(host, "/ws");
  }
  DecodedMessage read() {
    beast::flat_buffer buffer;
    ws_.read(buffer);
    return decodeMessage(beast::buffers_to_string(buffer.data()));
  }
  // Messages up to and including "synced".
  std::vector<DecodedMessage> readUntilSynced() {
    std::vector<DecodedMessage> out;
    for (;;) {
      out.push_back(read());
      if (out.back().header.value("type", "") == "synced") return out;
    }
  }
  void send(const std::string& text) {
    ws_.text(true);
    ws_.write(asio::buffer(text));
  }
  tcp::socket& socket() { return ws_.next_layer(); }

 private:
  asio::io_context ioc_;
  websocket::stream<tcp::socket> ws_;
};

template <typename Predicate>
bool waitFor(Predicate p, double seconds = 5.0) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (p()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return p();
}

TEST(ViewWire, MessagesRoundTripAndCorruptOnesAreNamed) {
  const std::vector<float> positions = {1, 2, 3, 4, 5, 6};
  const std::vector<std::uint8_t> colours = {7, 8, 9};
  const Message m = encodeMessage({{"type", "mesh"}, {"id", "a"}},
                                  {{"positions", WireArray::Type::kF32, positions.data(), 6},
                                   {"colors", WireArray::Type::kU8, colours.data(), 3}});
  ASSERT_EQ(m->size() % 4, 0u);
  const DecodedMessage d = decodeMessage(*m);
  EXPECT_EQ(d.header["type"], "mesh");
  ASSERT_EQ(d.header["arrays"].size(), 2u);
  EXPECT_EQ(d.header["arrays"][1]["offset"], 24);  // after six floats
  float back[6];
  std::memcpy(back, d.payload.data(), sizeof(back));
  EXPECT_EQ(back[5], 6.0f);
  EXPECT_EQ(static_cast<std::uint8_t>(d.payload[24 + 2]), 9);

  EXPECT_THROW(decodeMessage("ab"), InputError);
  std::string cut = *m;
  cut.resize(cut.size() - 8);  // the colours' array runs past the end
  EXPECT_THROW(decodeMessage(cut), InputError);
  std::string bad_json = *m;
  bad_json[4] = '[';
  EXPECT_THROW(decodeMessage(bad_json), InputError);
}

TEST(ViewScene, ReadersGetEachChangedItemOnceInTheOrderItChanged) {
  Scene scene;
  scene.put("a", item("a", 1));
  scene.put("b", item("b", 2));
  std::vector<Message> first;
  const std::uint64_t v = scene.changesSince(0, &first);
  ASSERT_EQ(first.size(), 2u);
  scene.put("a", item("a", 3));
  scene.put("a", item("a", 4));  // replaces 3: a reader behind never sees it
  scene.remove("b");
  std::vector<Message> next;
  scene.changesSince(v, &next);
  ASSERT_EQ(next.size(), 2u);
  EXPECT_EQ(decodeMessage(*next[0]).header["value"], 4);
  EXPECT_EQ(decodeMessage(*next[1]).header["type"], "remove");
  std::vector<Message> fresh;
  scene.changesSince(0, &fresh);  // a new reader does not get removals of what it never saw
  ASSERT_EQ(fresh.size(), 1u);
  EXPECT_EQ(scene.size(), 1u);
}

TEST(ViewServer, ServesThePageFilesAndNothingElse) {
  Served s;
  const auto port = s.server->port();
  const std::string index = rawHttp(port, "GET / HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(statusOf(index), 200);
  EXPECT_NE(index.find("Content-Type: text/html"), std::string::npos);
  EXPECT_NE(index.find("/viewer.js"), std::string::npos);
  const std::string bundle = rawHttp(port, "HEAD /viewer.js HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(statusOf(bundle), 200);
  EXPECT_NE(bundle.find("text/javascript"), std::string::npos);
  for (const char* target : {"/../../../../etc/passwd", "/%2e%2e/%2e%2e/etc/passwd", "//etc/passwd",
                             "/index.html/../../CMakeLists.txt", "/web/index.html", "/ws/../index.html"}) {
    const std::string r = rawHttp(port, std::string("GET ") + target + " HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
    EXPECT_EQ(statusOf(r), 404) << target;
    EXPECT_EQ(r.find("root:"), std::string::npos) << target;
  }
  EXPECT_EQ(statusOf(rawHttp(port, "POST / HTTP/1.1\r\nHost: x\r\nContent-Length: 2\r\nConnection: close\r\n\r\nhi")), 405);
  EXPECT_EQ(statusOf(rawHttp(port, "DELETE /index.html HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n")), 405);
}

TEST(ViewServer, MalformedAndOversizedRequestsAreRefusedAndTheServerGoesOn) {
  Served s;
  const auto port = s.server->port();
  EXPECT_EQ(statusOf(rawHttp(port, "BLAH\r\n\r\n")), 400);
  EXPECT_EQ(statusOf(rawHttp(port, "GET / HTTP/9.9.9\r\n\r\n")), 400);
  EXPECT_EQ(statusOf(rawHttp(port, "GET / HTTP/1.1\r\nHost: x\r\nX-Big: " + std::string(20000, 'a') + "\r\n\r\n")), 400);
  EXPECT_EQ(statusOf(rawHttp(port, "POST / HTTP/1.1\r\nHost: x\r\nContent-Length: 1000000\r\n\r\n" + std::string(1000, 'x'))), 400);
  {
    // Binary garbage, then the socket closed by the client half-way.
    asio::io_context ioc;
    tcp::socket socket(ioc);
    socket.connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port));
    const std::string junk = std::string("\x16\x03\x01\x02\x00\x01\x00\x01\xfc\x03\x03", 11) + std::string(300, '\xff');
    asio::write(socket, asio::buffer(junk));
  }
  EXPECT_GE(s.server->stats().refused, 4u);
  EXPECT_EQ(statusOf(rawHttp(port, "GET / HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n")), 200);
}

TEST(ViewServer, AClientGetsTheSceneThenSyncedThenEachChange) {
  Served s;
  s.scene.put("a", item("a", 1));
  s.scene.put("b", item("b", 2));
  WsClient client(s.server->port());
  const auto first = client.readUntilSynced();
  ASSERT_EQ(first.size(), 3u);
  EXPECT_EQ(first[0].header["id"], "a");
  EXPECT_EQ(first[1].header["id"], "b");
  s.scene.put("b", item("b", 5));
  const DecodedMessage change = client.read();
  EXPECT_EQ(change.header["id"], "b");
  EXPECT_EQ(change.header["value"], 5);
  s.scene.remove("a");
  EXPECT_EQ(client.read().header["type"], "remove");
}

TEST(ViewServer, ASlowClientGetsTheLatestStateNotEveryUpdate) {
  Served s;
  s.scene.put("big", item("big", 0, 256 * 1024));  // 1 MiB messages: the socket holds only a few
  WsClient slow(s.server->port());
  slow.readUntilSynced();
  constexpr int kUpdates = 200;
  for (int i = 1; i <= kUpdates; ++i) s.scene.put("big", item("big", i, 256 * 1024));
  // The client now reads: every message it gets is a newer state, and it ends at the last one
  // having received far fewer than all (the server never queued them).
  int received = 0, last = 0;
  while (last != kUpdates) {
    const DecodedMessage m = slow.read();
    const int value = m.header["value"];
    EXPECT_GT(value, last);
    last = value;
    ++received;
  }
  EXPECT_LT(received, kUpdates / 4) << "a slow client was sent " << received << " of " << kUpdates << " updates";
}

TEST(ViewServer, ManyClientsAndOneGoneMidStream) {
  Served s;
  for (int i = 0; i < 30; ++i) s.scene.put("item" + std::to_string(i), item("x", i, 16 * 1024));
  std::vector<std::unique_ptr<WsClient>> clients;
  for (int i = 0; i < 12; ++i) clients.push_back(std::make_unique<WsClient>(s.server->port()));
  clients[3]->read();
  clients[3]->socket().close();  // gone after its first message
  clients[3].reset();
  for (std::size_t i = 0; i < clients.size(); ++i) {
    if (!clients[i]) continue;
    EXPECT_EQ(clients[i]->readUntilSynced().size(), 31u) << "client " << i;
  }
  EXPECT_TRUE(waitFor([&] { return s.server->stats().clients == 11; })) << s.server->stats().clients;
  s.scene.put("item0", item("x", 100));
  for (auto& c : clients) {
    if (c) {
      EXPECT_EQ(c->read().header["value"], 100);
    }
  }
}

TEST(ViewServer, AnotherOriginAndTooManyClientsAreRefused) {
  ServerOptions options;
  options.max_clients = 2;
  Served s(options);
  const auto port = s.server->port();
  EXPECT_THROW(WsClient(port, "http://evil.example"), beast::system_error);
  WsClient same(port, "http://" + s.host());
  WsClient no_origin(port);  // a program, not a page
  EXPECT_TRUE(waitFor([&] { return s.server->stats().clients == 2; }));
  EXPECT_THROW(WsClient(port, ""), beast::system_error);  // the third
  EXPECT_GE(s.server->stats().refused, 2u);
}

TEST(ViewServer, RequestsAreAnsweredAndBadOnesGetAnErrorOrCloseTheSession) {
  ServerOptions options;
  options.max_request_bytes = 1024;
  Served s(options, [](const nlohmann::json& request) -> Message {
    if (request.value("type", "") == "boom") throw InputError("no such thing");
    return encodeMessage({{"type", "answer"}, {"id", request.value("id", 0)}, {"distance", 0.25}});
  });
  WsClient client(s.server->port());
  client.readUntilSynced();
  client.send(R"({"type": "query", "id": 7, "point": [0, 0, 1]})");
  const DecodedMessage answer = client.read();
  EXPECT_EQ(answer.header["type"], "answer");
  EXPECT_EQ(answer.header["id"], 7);
  client.send("not json {");
  EXPECT_EQ(client.read().header["type"], "error");
  client.send(R"({"type": "boom"})");
  const DecodedMessage error = client.read();
  EXPECT_EQ(error.header["type"], "error");
  EXPECT_EQ(error.header["message"], "no such thing");
  // Over the size limit: the session is closed; the server goes on.
  client.send(std::string(4096, ' '));
  EXPECT_THROW(client.read(), beast::system_error);
  WsClient next(s.server->port());
  EXPECT_EQ(next.readUntilSynced().size(), 1u);
}

TEST(ViewServer, MalformedWebSocketFramesCloseOnlyThatSession) {
  Served s;
  s.scene.put("a", item("a", 1));
  WsClient bad(s.server->port());
  bad.readUntilSynced();
  // A frame with reserved bits and opcode 0xB, unmasked (clients must mask): a protocol error.
  const std::string frame("\xF3\x05hello", 7);
  asio::write(bad.socket(), asio::buffer(frame));
  // The server answers with a close frame; the session ends when the client's socket closes.
  std::array<std::uint8_t, 2> close{};
  asio::read(bad.socket(), asio::buffer(close));
  EXPECT_EQ(close[0], 0x88) << "expected a close frame";
  bad.socket().close();
  EXPECT_TRUE(waitFor([&] { return s.server->stats().clients == 0; }));
  WsClient good(s.server->port());
  EXPECT_EQ(good.readUntilSynced().size(), 2u);
}

TEST(ViewServer, AnAddressInUseIsAnInputErrorNamingIt) {
  Served first;
  Scene scene;
  ServerOptions options;
  options.port = first.server->port();
  Server second(scene, options);
  try {
    second.start();
    FAIL() << "a second server bound the same port";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(std::to_string(options.port)), std::string::npos) << e.what();
  }
  options.port = 0;
  options.bind_address = "not-an-address";
  Server third(scene, options);
  EXPECT_THROW(third.start(), InputError);
}

}  // namespace
}  // namespace strata::view
