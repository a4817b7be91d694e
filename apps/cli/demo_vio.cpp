#include "cli/demo_vio.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include "strata/sim/sim_setup.h"
#include "strata/core/error.h"
#include "strata/odometry/pipeline/vio_replay.h"
#include "strata/sim/session/stereo_recording.h"
#include "strata/trajectory/trajectory_error.h"

namespace strata::apps {
namespace {

using Clock = std::chrono::steady_clock;

std::int64_t toNs(double t_s, std::int64_t start_ns) { return start_ns + std::llround(t_s * 1e9); }

odometry::ReplayResult runVio(const sim::StereoRecording& recording, const DemoVioOptions& o,
                              ProgressBar& progress, std::size_t& done) {
  odometry::VioPipelineConfig config;
  config.backend.window_size = o.window;
  config.anchor_W_B = odometry::truthAnchor(recording.groundTruth());
  odometry::VioPipeline pipeline(recording.calibration(), config);
  odometry::ReplayInput input;
  input.imu = &recording.imu();
  input.frame_timestamps_ns = recording.frameTimestamps();
  input.load = [&](std::size_t k) {
    sim::GreyFrame frame = recording.renderFrame(k);
    return euroc::StereoImages{std::move(frame.eyes.at(0)), std::move(frame.eyes.at(1))};
  };
  const std::size_t start = done;
  input.on_pushed = [&](std::size_t pushed, const odometry::PipelineStats& s) {
    done = start + pushed;
    progress.update(done, std::to_string(s.frames_tracking) + " tracked, " +
                              std::to_string(s.failures) + " failures");
  };
  return odometry::replayVio(pipeline, input);
}

/// The fused poses against the truth of the same frames, without alignment.
void poseErrors(const sim::SimSessionDataset& session, VioSessionResult& r) {
  std::vector<trajectory::StampedPose> estimate, truth;
  for (std::size_t i = 0; i < session.size(); ++i) {
    estimate.push_back({session.timestamp(i), session.givenPoses()[i]});
    truth.push_back({session.timestamp(i), session.truePoses()[i]});
  }
  const trajectory::TrajectoryError e = trajectory::evaluateTrajectory(estimate, truth, trajectory::Alignment::kNone);
  r.ate_rmse_m = e.ate_rmse_m;
  r.ate_max_m = e.ate_max_m;
  r.rotation_rmse_deg = e.rotation_rmse_deg;
}

}  // namespace

void DemoVioOptions::validate() const {
  if (window < 2) throw InputError("--vio-window must be at least 2");
  sim::stereoRecordingConfig(width_px, height_px, true).validate();
}

std::size_t vioFrameCount(const sim::SimSessionDataset& session, const DemoVioOptions& o) {
  return sim::stereoFrameCount(session, sim::stereoRecordingConfig(o.width_px, o.height_px, true));
}

VioSessionResult useVioPoses(sim::SimSessionDataset& session, const DemoVioOptions& o, bool noise,
                             ProgressBar& progress, std::size_t& done) {
  const sim::StereoRecordingConfig config = sim::stereoRecordingConfig(o.width_px, o.height_px, noise);
  const sim::StereoRecording recording(session, config);
  const odometry::ReplayResult vio = runVio(recording, o, progress, done);
  VioSessionResult r;
  r.stereo_frames = recording.frameTimestamps().size();
  r.tracked = vio.tracked.size();
  r.failures = vio.stats.failures;
  r.render_s = vio.image_load_s;
  r.vio_s = vio.wall_s - vio.image_load_s;
  r.rgbd_frames = session.size();
  const std::int64_t start_ns = config.imu.start_time_ns;
  if (!vio.tracked.empty())
    r.first_tracking_s = 1e-9 * (vio.tracked.front().timestamp_ns - start_ns);
  // Neighbouring camera frames, with some slack: one missing frame between two is a gap.
  const auto max_gap_ns = static_cast<std::int64_t>(1.5e9 / config.camera_rate_hz);
  std::vector<std::optional<Eigen::Isometry3d>> poses;
  for (std::size_t i = 0; i < session.size(); ++i) {
    const std::int64_t t_ns = toNs(session.timestamp(i), start_ns);
    poses.push_back(odometry::interpolateCameraPose(vio.tracked, t_ns, max_gap_ns));
    if (poses.back()) continue;
    if (vio.tracked.empty() || t_ns < vio.tracked.front().timestamp_ns)
      ++r.skipped_before_tracking;
    else if (t_ns > vio.tracked.back().timestamp_ns)
      ++r.skipped_after_tracking;
    else
      ++r.skipped_in_gaps;
  }
  if (r.fused() == 0) {
    const auto& log = vio.stats.failure_log;
    throw Error(session.name() + ": the VIO tracked none of its " + std::to_string(r.rgbd_frames) +
                " RGB-D frames (" + std::to_string(r.tracked) + " of " +
                std::to_string(r.stereo_frames) + " stereo frames tracked" +
                (log.empty() ? std::string() : "; last failure: " + log.back().second) + ")");
  }
  session.replaceGivenPoses(poses);
  poseErrors(session, r);
  return r;
}

}  // namespace strata::apps
