#include "strata/core/clock.h"
#include "strata/odometry/pipeline/vio_replay.h"

#include <algorithm>
#include <chrono>

#include "strata/core/pose_interpolation.h"

namespace strata::odometry {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

ReplayResult replayVio(VioPipeline& pipeline, const ReplayInput& input) {
  ReplayResult result;
  result.stereo = pipeline.stereo();
  const auto collect = [&](std::vector<PipelineFrame> done) {
    for (auto& f : done) {
      if (input.on_processed) input.on_processed(f);
      if (f.status == VioStatus::kTracking) result.tracked.push_back(std::move(f));
    }
  };
  const std::vector<euroc::ImuSample> none;
  const std::vector<euroc::ImuSample>& imu = input.imu != nullptr ? *input.imu : none;
  const std::size_t frames = input.max_frames > 0
                                 ? std::min(input.max_frames, input.frame_timestamps_ns.size())
                                 : input.frame_timestamps_ns.size();
  const Clock::time_point start = Clock::now();
  std::size_t i = 0;
  for (std::size_t k = 0; k < frames; ++k) {
    const std::int64_t t_ns = input.frame_timestamps_ns[k];
    for (; i < imu.size() && imu[i].timestamp_ns <= t_ns; ++i) collect(pipeline.pushImu(imu[i]));
    const Clock::time_point load = Clock::now();
    const euroc::StereoImages images = input.load(k);
    result.image_load_s += secondsSince(load);
    collect(pipeline.pushFrame(t_ns, images.left, images.right));
    if (input.on_pushed) input.on_pushed(k + 1, pipeline.stats());
  }
  // The samples after the last frame pushed (up to the next frame's time, when frames are left
  // out) complete a frame still waiting for its IMU.
  const bool cut = frames < input.frame_timestamps_ns.size();
  for (; i < imu.size() && !(cut && imu[i].timestamp_ns > input.frame_timestamps_ns[frames]); ++i)
    collect(pipeline.pushImu(imu[i]));
  pipeline.flush();
  result.wall_s = secondsSince(start);
  result.stats = pipeline.stats();
  return result;
}

std::function<std::optional<Eigen::Isometry3d>(std::int64_t)> truthAnchor(
    const std::vector<euroc::GroundTruthState>& truth) {
  const auto* states = &truth;
  return [states](std::int64_t t_ns) { return euroc::interpolateGroundTruth(*states, t_ns); };
}

std::optional<Eigen::Isometry3d> interpolateCameraPose(const std::vector<PipelineFrame>& tracked,
                                                       std::int64_t timestamp_ns,
                                                       std::int64_t max_gap_ns) {
  return interpolateStamped(
      tracked, timestamp_ns, max_gap_ns, [](const PipelineFrame& f) { return f.timestamp_ns; },
      [](const PipelineFrame& f) { return f.T_W_C; });
}

}  // namespace strata::odometry
