#include "localizer_node/localizer_options.h"

#include <CLI/CLI.hpp>
#include <string>

#include "cli/option_checks.h"
#include "strata/core/error.h"

namespace strata::apps {

// Limits: far beyond any use, low enough that a typo is refused before it is acted on.
constexpr int kMaxEvery = 10'000;
constexpr double kMaxSeconds = 86400.0;  // a day

void LocalizerOptions::validate() const {
  if (db_path.empty()) throw InputError("--db: the prior map's database is needed");
  requireCount(every, "--every", 1, kMaxEvery);
  requireNumberIn(max_odometry_gap_s, "--max-odometry-gap", "seconds", 1e-3, kMaxSeconds);
  requireNumberIn(max_idle_s, "--max-idle-s", "seconds; 0: run until a signal", 0.0, kMaxSeconds);
  requireNumberIn(status_period_s, "--status-period", "seconds; 0: no progress lines", 0.0,
                  kMaxSeconds);
  requireCount(map.threads, "--load-threads", 1, 256);
  const LocalizerChannels& c = channels;
  for (const std::string* name : {&c.rgbd, &c.camera_info, &c.odometry, &c.pose, &c.status}) {
    if (name->empty()) throw InputError("channel names must not be empty");
  }
  // NOTE: with one URL, listening to its own output would feed map-frame poses back as odometry.
  if (output_url.empty() || output_url == url) {
    for (const std::string* out : {&c.pose, &c.status}) {
      for (const std::string* in : {&c.rgbd, &c.camera_info, &c.odometry}) {
        if (*out == *in) {
          throw InputError("channel '" + *out + "' is both an input and an output (choose " +
                           "another --pose-channel or --status-channel)");
        }
      }
    }
  }
  if (c.pose == c.status) throw InputError("--pose-channel and --status-channel are the same");
  map.validate();
  localizer.validate();
  fusion.validate();
}

void addLocalizerOptions(CLI::App& app, LocalizerOptions& o) {
  app.add_option("--db", o.db_path, "Map database of the prior map (opened read-only)")->required();
  app.add_option("--url", o.url, "LCM URL to listen on (udpm with ttl=0 stays on this host)")
      ->capture_default_str();
  app.add_option("--output-url", o.output_url, "LCM URL to publish on (default: --url)");
  app.add_option("--every", o.every,
                 "Localise every Nth frame (the others, and those arriving while the localiser "
                 "is busy, get the last correction)")
      ->capture_default_str();
  app.add_option("--max-odometry-gap", o.max_odometry_gap_s,
                 "Odometry poses further apart are counted as gaps (frames in a gap get no pose), "
                 "seconds")
      ->check(finiteNumber())
      ->capture_default_str();
  app.add_option("--max-idle-s", o.max_idle_s,
                 "Exit once no frame or odometry came for this long, seconds (0: run until "
                 "SIGINT/SIGTERM)")
      ->check(finiteNumber())
      ->capture_default_str();
  app.add_option("--status-period", o.status_period_s,
                 "A progress line on stderr this often, seconds (0: none)")
      ->check(finiteNumber())
      ->capture_default_str();
  app.add_option("--report", o.report_path, "JSON summary written at exit");
  app.add_option("--load-threads", o.map.threads, "Threads loading the prior map")
      ->capture_default_str();
  app.add_option("--rgbd-channel", o.channels.rgbd)->capture_default_str();
  app.add_option("--camera-info-channel", o.channels.camera_info)->capture_default_str();
  app.add_option("--odometry-channel", o.channels.odometry,
                 "pose_t T_O_C in (strata-vio's --pose-channel)")
      ->capture_default_str();
  app.add_option("--pose-channel", o.channels.pose,
                 "pose_t T_W_C out, map frame (strata-mapper's --pose-channel)")
      ->capture_default_str();
  app.add_option("--status-channel", o.channels.status, "localization_status_t out")
      ->capture_default_str();
  app.add_flag("--quiet", o.quiet, "Log only problems");
}

}  // namespace strata::apps
