#pragma once
// Options of strata-view (the live viewer): where it listens on LCM, which channels, how it
// serves the page (as `strata view`: --bind, --port), how long.
#include <string>

#include "view/live_view.h"

namespace CLI {
class App;
}

namespace strata::apps {

struct LiveOptions {
  /// LCM URL to listen on (the processes' default: multicast on this host only).
  std::string url = lcm_io::kDefaultUrl;
  view::LiveChannels channels;
  /// Address to serve on: loopback by default; "0.0.0.0" exposes the view to the network.
  std::string bind_address = "127.0.0.1";
  int port = 8765;             // 0: any free one
  double serve_seconds = 0.0;  // 0: until SIGINT/SIGTERM
  bool quiet = false;

  /// Throws InputError naming the bad option.
  void validate() const;
};

/// Registers strata-view's options on `app`.
void addLiveOptions(CLI::App& app, LiveOptions& options);

}  // namespace strata::apps
