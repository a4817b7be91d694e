#pragma once
// A page rendered by headless Chromium, as PNG bytes: the picture `strata view --screenshot` writes,
// so the pictures in the docs come from the viewer itself. Chromium (Debian's `chromium`) is started
// with a private, temporary profile and no network beyond what the page asks (no background
// services, no component updates), driven over its DevTools protocol (a WebSocket, Boost.Beast),
// and stopped when the picture is taken. WebGL runs on SwiftShader (software), so it works with no
// GPU.
// Errors: strata::Error naming the step (the browser missing or failing to start, the page not
// ready within the timeout, the protocol answering with an error). Not thread safe for one call.
#include <string>

namespace strata::view {

struct ScreenshotOptions {
  std::string browser = "/usr/bin/chromium";
  int width = 1280;
  int height = 800;
  /// From the browser's start to the page being ready.
  double timeout_s = 300.0;
  /// A JavaScript expression the page must make true before the picture is taken.
  std::string ready_expression = "window.strata && window.strata.synced && window.strata.firstSceneDrawn";
  /// Frames to let the page draw after it is ready (the camera framing, the slice texture).
  int settle_frames = 10;
};

/// The PNG of `url` (an http://127.0.0.1 page) at options.width x options.height.
std::string screenshotPage(const std::string& url, const ScreenshotOptions& options);

}  // namespace strata::view
