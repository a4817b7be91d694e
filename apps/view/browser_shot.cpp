#include "view/browser_shot.h"

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

#include "strata/core/error.h"

extern char** environ;

namespace strata::view {
namespace {

namespace fs = std::filesystem;
namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;
using Clock = std::chrono::steady_clock;

std::string decodeBase64(const std::string& in) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  std::string out;
  out.reserve(in.size() * 3 / 4);
  unsigned int bits = 0;
  int count = 0;
  for (char c : in) {
    const int v = value(c);
    if (v < 0) continue;  // padding and line breaks
    bits = (bits << 6) | static_cast<unsigned int>(v);
    count += 6;
    if (count >= 8) {
      count -= 8;
      out.push_back(static_cast<char>((bits >> count) & 0xffu));
    }
  }
  return out;
}

// Chromium with a private profile; killed and its profile removed when this goes out of scope.
class Browser {
 public:
  Browser(const ScreenshotOptions& o) {
    if (access(o.browser.c_str(), X_OK) != 0) {
      throw Error("screenshot: no browser at '" + o.browser +
                  "' (Debian: apt-get install chromium; or --browser PATH)");
    }
    // A private profile in the system's temporary folder (TMPDIR when set).
    std::error_code ec;
    std::string pattern = (fs::temp_directory_path(ec) / "strata-view-browser-XXXXXX").string();
    if (ec || !mkdtemp(pattern.data())) {
      throw Error("screenshot: cannot make a temporary browser profile in " + pattern);
    }
    profile_ = pattern;
    const std::vector<std::string> args = {
        o.browser, "--headless=new", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader",
        "--use-angle=swiftshader", "--no-first-run", "--disable-background-networking",
        "--disable-component-update", "--disable-sync", "--disable-default-apps",
        "--disable-extensions", "--hide-scrollbars", "--mute-audio",
        "--remote-debugging-address=127.0.0.1", "--remote-debugging-port=0",
        "--user-data-dir=" + profile_,
        "--window-size=" + std::to_string(o.width) + "," + std::to_string(o.height), "about:blank"};
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    // The browser's own chatter (DBus, fonts) is not the user's concern.
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, (profile_ + "/stderr.log").c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int rc = posix_spawn(&pid_, o.browser.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) {
      pid_ = -1;
      throw Error("screenshot: cannot start '" + o.browser + "'");
    }
  }
  ~Browser() {
    if (pid_ > 0) {
      kill(pid_, SIGTERM);
      for (int i = 0; i < 50; ++i) {
        if (waitpid(pid_, nullptr, WNOHANG) == pid_) {
          pid_ = -1;
          break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      }
      if (pid_ > 0) {
        kill(pid_, SIGKILL);
        waitpid(pid_, nullptr, 0);
      }
    }
    std::error_code ec;
    fs::remove_all(profile_, ec);
  }

  // The DevTools port, once the browser has written it.
  int devtoolsPort(Clock::time_point deadline) {
    const fs::path file = fs::path(profile_) / "DevToolsActivePort";
    while (Clock::now() < deadline) {
      std::ifstream in(file);
      int port = 0;
      if (in >> port && port > 0) return port;
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        std::ifstream log(profile_ + "/stderr.log");
        std::string line, last;
        while (std::getline(log, line)) {
          if (!line.empty()) last = line;
        }
        throw Error("screenshot: the browser exited at start (" + last + ")");
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    throw Error("screenshot: the browser did not open its DevTools port in time");
  }

 private:
  pid_t pid_ = -1;
  std::string profile_;
};

// One DevTools session over a page target's WebSocket.
class DevTools {
 public:
  DevTools(int port, const std::string& path) : ws_(ioc_) {
    tcp::resolver resolver(ioc_);
    asio::connect(ws_.next_layer(), resolver.resolve("127.0.0.1", std::to_string(port)));
    ws_.read_message_max(64u << 20);
    ws_.handshake("127.0.0.1:" + std::to_string(port), path);
  }
  nlohmann::json call(const std::string& method, nlohmann::json params = nlohmann::json::object()) {
    const int id = ++next_id_;
    ws_.text(true);
    ws_.write(asio::buffer(nlohmann::json{{"id", id}, {"method", method}, {"params", params}}.dump()));
    for (;;) {
      beast::flat_buffer buffer;
      ws_.read(buffer);
      const auto reply = nlohmann::json::parse(beast::buffers_to_string(buffer.data()), nullptr, false);
      if (reply.is_discarded() || reply.value("id", -1) != id) continue;  // events
      if (reply.contains("error")) {
        throw Error("screenshot: " + method + " failed: " + reply["error"].dump());
      }
      return reply.value("result", nlohmann::json::object());
    }
  }

 private:
  asio::io_context ioc_;
  websocket::stream<tcp::socket> ws_;
  int next_id_ = 0;
};

// The WebSocket path of the browser's first page target (GET /json/list).
std::string pageTargetPath(int port) {
  asio::io_context ioc;
  tcp::resolver resolver(ioc);
  beast::tcp_stream stream(ioc);
  stream.connect(resolver.resolve("127.0.0.1", std::to_string(port)));
  http::request<http::empty_body> request(http::verb::get, "/json/list", 11);
  request.set(http::field::host, "127.0.0.1:" + std::to_string(port));
  http::write(stream, request);
  beast::flat_buffer buffer;
  http::response<http::string_body> response;
  http::read(stream, buffer, response);
  const auto targets = nlohmann::json::parse(response.body(), nullptr, false);
  if (targets.is_array()) {
    for (const auto& t : targets) {
      if (t.value("type", "") != "page") continue;
      const std::string url = t.value("webSocketDebuggerUrl", "");
      const auto slash = url.find('/', url.find("://") + 3);
      if (slash != std::string::npos) return url.substr(slash);
    }
  }
  throw Error("screenshot: the browser has no page to drive");
}

}  // namespace

std::string screenshotPage(const std::string& url, const ScreenshotOptions& o) {
  const auto deadline = Clock::now() + std::chrono::milliseconds(static_cast<long>(o.timeout_s * 1000));
  Browser browser(o);
  const int port = browser.devtoolsPort(deadline);
  std::string path;
  while (path.empty()) {
    try {
      path = pageTargetPath(port);
    } catch (const std::exception&) {
      if (Clock::now() > deadline) throw;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }
  DevTools tools(port, path);
  tools.call("Page.enable");
  tools.call("Emulation.setDeviceMetricsOverride",
             {{"width", o.width}, {"height", o.height}, {"deviceScaleFactor", 1}, {"mobile", false}});
  tools.call("Page.navigate", {{"url", url}});
  auto evaluate = [&](const std::string& expression) {
    const auto result = tools.call("Runtime.evaluate", {{"expression", expression}, {"returnByValue", true}});
    return result.value("result", nlohmann::json::object()).value("value", nlohmann::json());
  };
  for (;;) {
    const auto ready = evaluate("Boolean(" + o.ready_expression + ")");
    if (ready.is_boolean() && ready.get<bool>()) break;
    if (Clock::now() > deadline) {
      throw Error("screenshot: the page at " + url + " was not ready within " +
                  std::to_string(static_cast<int>(o.timeout_s)) + " s (" + o.ready_expression + ")");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  const auto frames = evaluate("window.strata ? window.strata.framesDrawn : 0");
  const long start = frames.is_number() ? frames.get<long>() : 0;
  while (Clock::now() < deadline) {
    const auto now = evaluate("window.strata ? window.strata.framesDrawn : 0");
    if (!now.is_number() || now.get<long>() >= start + o.settle_frames) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const auto shot = tools.call("Page.captureScreenshot", {{"format", "png"}});
  const std::string png = decodeBase64(shot.value("data", ""));
  if (png.size() < 8 || png.compare(1, 3, "PNG") != 0) throw Error("screenshot: the browser sent no PNG");
  return png;
}

}  // namespace strata::view
