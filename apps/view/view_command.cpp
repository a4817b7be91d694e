#include "view/view_command.h"

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <thread>

#include <CLI/CLI.hpp>

#include "cli/option_checks.h"
#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/core/output_paths.h"
#include "view/browser_shot.h"
#include "view/offline_view.h"
#include "view/server.h"

namespace strata::apps {
namespace {

std::atomic<bool> g_stop{false};
void onSignal(int) { g_stop = true; }

void validate(const ViewOptions& o) {
  if (o.path.empty()) throw InputError("no map, mesh or folder given");
  requireCount(o.port, "--port", 0, 65535);
  requireNumberIn(o.serve_seconds, "--serve-seconds", "seconds", 0.0, 86400.0 * 365);
  requireCount(o.width, "--width", 64, 8192);
  requireCount(o.height, "--height", 64, 8192);
  requireNumberIn(o.screenshot_timeout_s, "--screenshot-timeout", "seconds", 1.0, 3600.0);
  OutputPaths paths;
  if (std::filesystem::is_directory(o.path)) {
    paths.inputFolder(o.path, "PATH");
  } else {
    paths.inputFile(o.path, "PATH");
  }
  if (!o.screenshot_path.empty()) paths.outputFile(o.screenshot_path, "--screenshot");
  paths.check();
}

int runChecked(const ViewOptions& o) {
  validate(o);
  view::Scene scene;
  view::OfflineView offline(o.path, o.device, scene);
  view::ServerOptions server_options;
  server_options.bind_address = o.bind_address;
  server_options.port = static_cast<std::uint16_t>(o.port);
  view::Server server(scene, server_options,
                      [&offline](const nlohmann::json& request) { return offline.answer(request); });
  server.start();
  const std::string host = o.bind_address == "0.0.0.0" ? "127.0.0.1" : o.bind_address;
  const std::string url = "http://" + host + ":" + std::to_string(server.port()) + "/";
  if (!o.screenshot_path.empty()) {
    view::ScreenshotOptions shot;
    shot.browser = o.browser;
    shot.width = o.width;
    shot.height = o.height;
    shot.timeout_s = o.screenshot_timeout_s;
    const std::string png = view::screenshotPage(url, shot);
    writeFileAtomically(o.screenshot_path, std::vector<std::uint8_t>(png.begin(), png.end()));
    if (!o.quiet) {
      std::printf("strata view: %s: %s; screenshot %dx%d written to %s\n", o.path.c_str(),
                  offline.summary().c_str(), o.width, o.height, o.screenshot_path.c_str());
    }
    return 0;
  }
  if (!o.quiet) {
    std::printf("strata view: %s: %s\nstrata view: open %s (Ctrl-C stops)\n", o.path.c_str(),
                offline.summary().c_str(), url.c_str());
    std::fflush(stdout);
  }
  g_stop = false;
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  const auto start = std::chrono::steady_clock::now();
  while (!g_stop) {
    if (o.serve_seconds > 0 &&
        std::chrono::steady_clock::now() - start > std::chrono::duration<double>(o.serve_seconds)) {
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  server.stop();
  if (!o.quiet) {
    const view::ServerStats s = server.stats();
    std::printf("strata view: stopped; %llu sessions, %llu messages (%.1f MB) sent\n",
                static_cast<unsigned long long>(s.sessions_total),
                static_cast<unsigned long long>(s.messages_sent), s.bytes_sent / 1e6);
  }
  return 0;
}

}  // namespace

CLI::App* addViewCommand(CLI::App& app, ViewOptions& o) {
  CLI::App* view = app.add_subcommand(
      "view", "Show a map, mesh or run folder in the browser (http://127.0.0.1:8765/)");
  view->add_option("path", o.path, "A map (.strata), a mesh (.ply) or a run folder (strata demo, diff, objects, align, explore)")
      ->required();
  view->add_option("--bind", o.bind_address,
                   "Address to listen on; 127.0.0.1 keeps the view on this machine, 0.0.0.0 exposes it to the network")
      ->capture_default_str();
  view->add_option("--port", o.port, "TCP port (0: any free one)")->capture_default_str();
  view->add_option("--serve-seconds", o.serve_seconds, "Stop after this long (0: at Ctrl-C)")
      ->check(finiteNumber());
  view->add_option("--screenshot", o.screenshot_path,
                   "Render the page in headless Chromium, write this PNG and exit");
  view->add_option("--width", o.width, "Screenshot width, pixels")->capture_default_str();
  view->add_option("--height", o.height, "Screenshot height, pixels")->capture_default_str();
  view->add_option("--screenshot-timeout", o.screenshot_timeout_s,
                   "Seconds to wait for the browser and the page")
      ->check(finiteNumber())
      ->capture_default_str();
  view->add_option("--browser", o.browser, "Chromium to use for --screenshot")->capture_default_str();
  view->add_option("--device", o.device, "Vulkan device index or name substring (env STRATA_DEVICE)");
  view->add_flag("--quiet", o.quiet, "Print nothing but errors");
  return view;
}

int runView(const ViewOptions& options) {
  try {
    return runChecked(options);
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata view: input error: %s\n", e.what());
    return 2;
  } catch (const DeviceError& e) {
    std::fprintf(stderr, "strata view: device error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata view: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::apps
