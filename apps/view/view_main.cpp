// strata-view: the live viewer. Subscribes to what strata-mapper, strata-vio and strata-play
// publish on LCM (view/live_view.h says what is shown) and serves it to a browser as `strata view`
// serves saved results: http://127.0.0.1:8765/. Publishes nothing. Serves until SIGINT/SIGTERM or
// for --serve-seconds.
//
// Exit codes: 0 served, 2 bad input (an option, an LCM URL that cannot be opened, an address or
// port that cannot be bound: all before serving), 1 other.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <thread>

#include "cli/option_checks.h"
#include "strata/core/error.h"
#include "strata/lcm/stop_signal.h"
#include "view/live_options.h"
#include "view/live_view.h"
#include "view/server.h"

namespace {

using namespace strata;

/// How long one wait for LCM messages lasts: the stop flag and the flush are checked this often.
constexpr int kReceiveTimeoutMs = 50;

int runLive(const apps::LiveOptions& o, const std::atomic<bool>& stop) {
  o.validate();
  lcm::LCM lcm(o.url);
  if (!lcm.good()) throw InputError("LCM URL '" + o.url + "' could not be opened");
  view::Scene scene;
  const std::string title = "live · " + o.url.substr(0, o.url.find('?'));  // no URL options
  view::LiveView live(lcm, scene, o.channels, title, [](const std::string& line) {
    std::fprintf(stderr, "strata-view: %s\n", line.c_str());
  });
  view::ServerOptions server_options;
  server_options.bind_address = o.bind_address;
  server_options.port = static_cast<std::uint16_t>(o.port);
  view::Server server(scene, server_options,
                      [&live](const nlohmann::json& request) { return live.answer(request); });
  server.start();
  if (!o.quiet) {
    const std::string host = o.bind_address == "0.0.0.0" ? "127.0.0.1" : o.bind_address;
    std::printf(
        "strata-view: listening on %s (mesh %s, stats %s, poses %s); open http://%s:%u/ "
        "(Ctrl-C stops)\n",
        o.url.c_str(), o.channels.mesh.c_str(), o.channels.stats.c_str(), o.channels.pose.c_str(),
        host.c_str(), static_cast<unsigned>(server.port()));
    std::fflush(stdout);
  }
  const auto start = std::chrono::steady_clock::now();
  bool reported = false;
  while (!stop) {
    if (o.serve_seconds > 0 &&
        std::chrono::steady_clock::now() - start > std::chrono::duration<double>(o.serve_seconds)) {
      break;
    }
    if (live.handle(kReceiveTimeoutMs) < 0 && !stop) {  // NOTE: a signal interrupts the wait too
      // NOTE: e.g. the end of a log file (file:// provider): keep serving what the scene holds.
      if (!reported) std::fprintf(stderr, "strata-view: LCM stopped delivering messages\n");
      reported = true;
      std::this_thread::sleep_for(std::chrono::milliseconds(kReceiveTimeoutMs));
    }
  }
  server.stop();
  if (!o.quiet) {
    const view::LiveCounters c = live.counters();
    const view::ServerStats s = server.stats();
    std::printf(
        "strata-view: stopped; %llu messages received (%llu bad, skipped), %llu mesh "
        "updates (%llu lost; mapper to scene %.1f ms last, %.1f ms at most), %llu blocks "
        "shown; %llu sessions, %llu messages (%.1f MB) sent\n",
        static_cast<unsigned long long>(c.messages),
        static_cast<unsigned long long>(c.bad_messages),
        static_cast<unsigned long long>(c.mesh_updates),
        static_cast<unsigned long long>(c.mesh_updates_lost), c.mesh_latency_ms_last,
        c.mesh_latency_ms_max, static_cast<unsigned long long>(c.blocks),
        static_cast<unsigned long long>(s.sessions_total),
        static_cast<unsigned long long>(s.messages_sent), s.bytes_sent / 1e6);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "strata-view: show what strata-mapper, strata-vio and strata-play publish on LCM in the "
      "browser (http://127.0.0.1:8765/); publishes nothing"};
  apps::LiveOptions options;
  apps::addLiveOptions(app, options);
  int exit_code = 0;
  if (!apps::parseCommandLine(app, argc, argv, &exit_code)) return exit_code;
  const std::atomic<bool>& stop = lcm_io::installStopSignals();
  try {
    return runLive(options, stop);
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata-view: input error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata-view: error: %s\n", e.what());
    return 1;
  }
}
