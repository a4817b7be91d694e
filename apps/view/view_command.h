#pragma once
// `strata view PATH`: serves a saved map (.strata), a mesh (.ply) or a run folder (strata demo,
// diff, objects, align, explore outputs) to a browser: http://127.0.0.1:8765/ shows the surface, the
// objects that moved with their boxes, the ESDF slice at a chosen height and the distance at a
// clicked point (view/offline_view.h says what is read). It serves until Ctrl-C, or for
// --serve-seconds. With --screenshot OUT.png it renders the page in headless Chromium
// (/usr/bin/chromium or --browser), writes the picture and exits.
//
// Exit codes: 0 served (or the screenshot written), 2 bad input (named before the server starts:
// the path, the options, the address or port that cannot be bound, --screenshot over an input),
// 3 device error, 1 other (the browser failed).
#include <cstdint>
#include <string>

namespace CLI {
class App;
}
namespace strata::apps {

struct ViewOptions {
  std::string path;
  std::string bind_address = "127.0.0.1";
  int port = 8765;
  double serve_seconds = 0.0;  // 0: until Ctrl-C
  std::string screenshot_path;
  int width = 1280, height = 800;  // of the screenshot
  std::string browser = "/usr/bin/chromium";
  /// The README demo's folder (2 M triangles) takes about 70 s with software WebGL on 2 cores.
  double screenshot_timeout_s = 300.0;
  std::string device;
  bool quiet = false;
};

CLI::App* addViewCommand(CLI::App& app, ViewOptions& options);
int runView(const ViewOptions& options);

}  // namespace strata::apps
