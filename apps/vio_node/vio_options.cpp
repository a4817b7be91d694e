#include "vio_node/vio_options.h"

#include <CLI/CLI.hpp>
#include <cmath>

#include "cli/option_checks.h"
#include "strata/core/error.h"

namespace strata::apps {

// Limits: far beyond any use, low enough that a typo is refused before it is acted on.
constexpr std::size_t kMaxQueueFrames = 10'000;
constexpr double kMaxSeconds = 86400.0;  // a day

void VioOptions::validate() const {
  if (calib_dir.empty())
    throw InputError("--calib: an EuRoC session folder (or its mav0/) is needed");
  if (queue_frames < 1 || queue_frames > kMaxQueueFrames) {
    throw InputError("--queue must be 1 to " + std::to_string(kMaxQueueFrames) + " frames, not " +
                     std::to_string(queue_frames));
  }
  requireNumberIn(max_idle_s, "--max-idle-s", "seconds; 0: run until a signal", 0.0, kMaxSeconds);
  requireNumberIn(status_period_s, "--status-period", "seconds; 0: no progress lines", 0.0,
                  kMaxSeconds);
  if (channels.stereo.empty() || channels.imu.empty() || channels.pose.empty()) {
    throw InputError("channel names must not be empty");
  }
  pipeline.validate();
}

void addVioOptions(CLI::App& app, VioOptions& o) {
  app.add_option("--calib", o.calib_dir,
                 "EuRoC session folder or its mav0/: cam0 (cam1) and imu0 sensor.yaml are read")
      ->required();
  app.add_flag("--mono", o.pipeline.mono, "Left camera only (scale from the IMU)");
  app.add_option("--url", o.url, "LCM URL to listen on (udpm with ttl=0 stays on this host)")
      ->capture_default_str();
  app.add_option("--output-url", o.output_url, "LCM URL to publish poses on (default: --url)");
  app.add_option("--queue", o.queue_frames,
                 "Frames waiting for the VIO; more arriving drop the oldest (counted)")
      ->capture_default_str();
  app.add_option("--max-idle-s", o.max_idle_s,
                 "Exit after this many seconds without a stereo or IMU message (0: never)")
      ->check(finiteNumber())
      ->capture_default_str();
  app.add_option("--status-period", o.status_period_s,
                 "Seconds between progress lines on stderr (0: none)")
      ->check(finiteNumber())
      ->capture_default_str();
  app.add_option("--summary", o.summary_path, "JSON summary written atomically at exit");
  app.add_option("--stereo-channel", o.channels.stereo)->capture_default_str();
  app.add_option("--imu-channel", o.channels.imu)->capture_default_str();
  app.add_option("--pose-channel", o.channels.pose)->capture_default_str();
  app.add_flag("--quiet", o.quiet, "No progress lines; log only problems");
  app.add_flag("--solver-log", o.solver_log,
               "Show the solver's own log (Ceres) on stderr; without it, only a count");
}

}  // namespace strata::apps
