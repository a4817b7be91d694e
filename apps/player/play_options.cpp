#include "player/play_options.h"

#include <CLI/CLI.hpp>
#include <cmath>

#include "cli/option_checks.h"
#include "strata/core/error.h"

namespace strata::apps {

// Limits of the counts: far beyond a real replay, low enough that a typo is refused before a
// camera path of that many poses is made (--sim-frames 1000000000 ran for minutes).
constexpr long long kMaxFrameIndex = 100'000'000;
constexpr long long kMaxSimFrames = 1'000'000;  // 9 hours at 30 Hz
constexpr long long kMaxWindow = 10'000;
constexpr double kMaxRate = 1000.0;              // times real time
constexpr double kMaxMapperTimeout_s = 86400.0;  // a day

void PlayOptions::validate() const {
  if (dataset.empty()) throw InputError("no dataset: pass a TUM folder or sim:WORLD[:SESSION]");
  requireNumberIn(rate, "--rate", "times real time; 0: flow control", 0.0, kMaxRate);
  requireCount(window, "--window", 1, kMaxWindow);
  requireCount(first, "--first", 0, kMaxFrameIndex);
  requireCount(frames, "--frames", 0, kMaxFrameIndex);
  requireCount(stride, "--stride", 1, kMaxFrameIndex);
  requireCount(sim_frames, "--sim-frames", 0, kMaxSimFrames);
  if (encoding.depth != "depth16" && encoding.depth != "depth32f") {
    throw InputError("--depth-encoding must be depth16 or depth32f");
  }
  requireNumber(mapper_timeout_s, "--mapper-timeout", "seconds", 0.0, false);
  requireNumberIn(mapper_timeout_s, "--mapper-timeout", "seconds", 0.0, kMaxMapperTimeout_s);
  if (with_stereo && rate == 0.0) {
    throw InputError(
        "--with-stereo needs --rate > 0 (a VIO takes the grey stream at its pace; "
        "there is no flow control for it)");
  }
  if (with_stereo && imu) throw InputError("--with-stereo sends mav0/'s IMU; drop --imu");
}

void addPlayOptions(CLI::App& app, PlayOptions& o) {
  app.add_option("dataset", o.dataset,
                 "TUM RGB-D folder, EuRoC session folder (mav0/), or sim:WORLD[:SESSION] "
                 "(e.g. sim:room:1)")
      ->required();
  app.add_option("--url", o.url, "LCM URL (udpm with ttl=0 stays on this host)")
      ->capture_default_str();
  app.add_option("--rate", o.rate,
                 "Speed relative to the recording; 0: as fast as the mapper fuses (flow control)")
      ->check(finiteNumber())
      ->capture_default_str();
  app.add_option("--window", o.window, "Flow control: frames sent but not yet fused")
      ->capture_default_str();
  app.add_option("--first", o.first, "Start at frame N of the recording (resume a replay)")
      ->capture_default_str();
  app.add_option("--frames", o.frames, "Send at most N frames (0: all)");
  app.add_option("--stride", o.stride, "Send every N-th frame")->capture_default_str();
  app.add_option("--sim-frames", o.sim_frames,
                 "Synthetic sessions: frames along the trajectory (0: all at 30 Hz)")
      ->capture_default_str();
  app.add_flag_callback(
      "--no-noise", [&o] { o.sim_noise = false; }, "Synthetic sessions: exact depth");
  app.add_flag("--separate-poses", o.separate_poses,
               "Send poses on the pose channel (the mapper interpolates) instead of in frames");
  app.add_flag("--imu", o.imu, "Synthetic sessions: also send IMU samples");
  app.add_flag_callback(
      "--no-poses", [&o] { o.poses = false; },
      "Send frames without poses and nothing on the pose channel (strata-vio provides them)");
  app.add_flag("--with-stereo", o.with_stereo,
               "A `strata sim --stereo` session folder: also send its mav0/ grey stereo + IMU, "
               "interleaved with the RGB-D frames in time order (RGB-D frames outside the grey "
               "recording are not sent; needs --rate > 0)");
  app.add_option("--depth-encoding", o.encoding.depth, "depth16 (compact) or depth32f (exact)")
      ->capture_default_str();
  app.add_flag_callback(
      "--keep-stamps", [&o] { o.restamp = false; },
      "Keep the recording's time stamps (default: stamp from now on)");
  app.add_flag_callback(
      "--no-end-session", [&o] { o.end_session = false; },
      "Do not end the mapper's session after the last frame");
  app.add_option("--save", o.save_path,
                 "After the last frame, ask the mapper to save its map here");
  app.add_option("--mapper-timeout", o.mapper_timeout_s,
                 "Seconds to wait for the mapper's stats and replies")
      ->check(finiteNumber())
      ->capture_default_str();
  app.add_option("--camera-id", o.camera_id)->capture_default_str();
  app.add_option("--rgbd-channel", o.rgbd_channel)->capture_default_str();
  app.add_option("--pose-channel", o.pose_channel)->capture_default_str();
  app.add_option("--imu-channel", o.imu_channel)->capture_default_str();
  app.add_option("--stereo-channel", o.stereo_channel, "EuRoC sessions: grey stereo frames")
      ->capture_default_str();
  app.add_option("--command-channel", o.command_channel)->capture_default_str();
  app.add_option("--stats-channel", o.stats_channel)->capture_default_str();
  app.add_flag("--quiet", o.quiet, "No progress bar");
}

}  // namespace strata::apps
