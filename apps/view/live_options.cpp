#include "view/live_options.h"

#include <CLI/CLI.hpp>

#include "cli/option_checks.h"
#include "strata/core/error.h"

namespace strata::apps {

void LiveOptions::validate() const {
  if (url.empty()) throw InputError("--lcm-url must not be empty");
  requireCount(port, "--port", 0, 65535);
  requireNumberIn(serve_seconds, "--serve-seconds", "seconds", 0.0, 86400.0 * 365);
  const view::LiveChannels& c = channels;
  for (const std::string* name :
       {&c.mesh, &c.esdf, &c.stats, &c.change, &c.objects, &c.pose, &c.rgbd, &c.camera_info}) {
    if (name->empty()) throw InputError("channel names must not be empty");
  }
}

void addLiveOptions(CLI::App& app, LiveOptions& o) {
  app.add_option("--lcm-url", o.url, "LCM URL to listen on (udpm with ttl=0 stays on this host)")
      ->capture_default_str();
  app.add_option("--bind", o.bind_address,
                 "Address to serve on; 127.0.0.1 keeps the view on this machine, 0.0.0.0 exposes "
                 "it to the network")
      ->capture_default_str();
  app.add_option("--port", o.port, "TCP port (0: any free one)")->capture_default_str();
  app.add_option("--serve-seconds", o.serve_seconds, "Stop after this long (0: at Ctrl-C)")
      ->check(finiteNumber());
  view::LiveChannels& c = o.channels;
  app.add_option("--mesh-channel", c.mesh, "mesh_update_t (strata-mapper)")->capture_default_str();
  app.add_option("--esdf-channel", c.esdf, "esdf_slice_t (strata-mapper)")->capture_default_str();
  app.add_option("--stats-channel", c.stats, "map_stats_t (strata-mapper)")->capture_default_str();
  app.add_option("--change-channel", c.change, "change_event_t (strata-mapper)")
      ->capture_default_str();
  app.add_option("--objects-channel", c.objects, "object_update_t (strata-mapper)")
      ->capture_default_str();
  app.add_option("--pose-channel", c.pose, "pose_t T_W_C (strata-vio, strata-play)")
      ->capture_default_str();
  app.add_option("--rgbd-channel", c.rgbd, "rgbd_frame_t: the poses inside frames (strata-play)")
      ->capture_default_str();
  app.add_option("--camera-info-channel", c.camera_info, "camera_info_t (strata-play)")
      ->capture_default_str();
  app.add_flag("--quiet", o.quiet, "Print nothing but errors");
}

}  // namespace strata::apps
