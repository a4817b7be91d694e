#pragma once
// Options of strata-localizer (the LCM process that localises live frames against a prior map):
// where it listens, which map it loads, how often it localises, what it publishes and when it
// stops.
#include <cstddef>
#include <string>

#include "strata/lcm/channels.h"
#include "strata/localize/localizer.h"
#include "strata/localize/pose_fusion.h"
#include "strata/localize/prior_map.h"

namespace CLI {
class App;
}

namespace strata::apps {

struct LocalizerChannels {
  std::string rgbd = lcm_io::kRgbdChannel;               // rgbd_frame_t in (colour + depth)
  std::string camera_info = lcm_io::kCameraInfoChannel;  // camera_info_t in
  std::string odometry = lcm_io::kPoseChannel;           // pose_t T_O_C in (strata-vio's poses)
  std::string pose = lcm_io::kMapPoseChannel;            // pose_t T_W_C out, map frame
  std::string status = lcm_io::kLocalizationChannel;     // localization_status_t out
};

struct LocalizerOptions {
  /// LCM URL to listen on; output_url "" publishes on the same.
  std::string url = lcm_io::kDefaultUrl;
  std::string output_url;
  LocalizerChannels channels;
  /// The prior map: a map database (`strata map import` / `strata align`), opened read-only.
  std::string db_path;
  /// Localise every Nth frame that has an odometry pose (1: every frame the localiser is free
  /// for). Localising takes ~50-150 ms on 2 cores; at a 20 Hz camera 5 gives 4 tries a second.
  int every = 5;
  /// Odometry poses further apart than this are accepted but counted and logged as gaps
  /// (frames inside a gap get no pose); seconds.
  double max_odometry_gap_s = 0.5;
  /// Exit once no frame or odometry message came for this long, seconds; 0: run until
  /// SIGINT/SIGTERM.
  double max_idle_s = 0.0;
  /// One progress line on stderr this often, seconds; 0: none.
  double status_period_s = 5.0;
  /// JSON summary written atomically at exit; "": none.
  std::string report_path;
  localize::PriorMapConfig map;
  localize::LocalizerConfig localizer;
  localize::FusionConfig fusion;
  bool quiet = false;

  /// Throws InputError naming the bad option.
  void validate() const;
};

/// Registers strata-localizer's options on `app`.
void addLocalizerOptions(CLI::App& app, LocalizerOptions& options);

}  // namespace strata::apps
