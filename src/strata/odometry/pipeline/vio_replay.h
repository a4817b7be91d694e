#pragma once
// A recorded session replayed through the VIO pipeline: IMU samples and camera frames merged in
// time order (at equal timestamps the IMU sample first, as euroc::EurocDataset::events()), each
// frame's images loaded only when it is pushed. What `strata odometry` does over an EuRoC folder
// and `strata demo --vio` over a simulated session in memory.
// Not thread safe (as the pipeline).
#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "strata/io/euroc_dataset.h"
#include "strata/io/euroc_types.h"
#include "strata/odometry/pipeline/vio_pipeline.h"

namespace strata::odometry {

struct ReplayInput {
  const std::vector<euroc::ImuSample>* imu = nullptr;  // time-ordered
  std::vector<std::int64_t> frame_timestamps_ns;       // increasing
  /// Grey images of frame k (k indexes frame_timestamps_ns; right empty for mono).
  std::function<euroc::StereoImages(std::size_t)> load;
  /// > 0: push only the first max_frames frames.
  std::size_t max_frames = 0;
  /// Optional: called for every processed frame, in time order (e.g. to report failures).
  std::function<void(const PipelineFrame&)> on_processed;
  /// Optional: called after each frame is pushed with the count pushed so far (progress).
  std::function<void(std::size_t, const PipelineStats&)> on_pushed;
};

struct ReplayResult {
  bool stereo = true;
  PipelineStats stats;
  std::vector<PipelineFrame> tracked;  // kTracking frames, in time order
  double wall_s = 0.0;                 // the whole replay, image loading included
  double image_load_s = 0.0;           // of which loading (decoding or rendering) images
};

/// Replays `input` through `pipeline` and flushes it. Throws what the pipeline and load throw.
ReplayResult replayVio(VioPipeline& pipeline, const ReplayInput& input);

/// An anchor for VioPipelineConfig::anchor_W_B from the body's time-ordered truth (interpolated;
/// euroc::interpolateGroundTruth). Borrows `truth`, which must outlive the pipeline.
std::function<std::optional<Eigen::Isometry3d>(std::int64_t)> truthAnchor(
    const std::vector<euroc::GroundTruthState>& truth);

/// The left camera's pose at `timestamp_ns` between the two tracked frames around it (translation
/// linear, rotation slerp; a frame at exactly that time gives its own). nullopt before the first
/// or after the last tracked frame, and where the two are more than `max_gap_ns` apart (a
/// tracking gap: frames between them failed or were not tracked).
std::optional<Eigen::Isometry3d> interpolateCameraPose(const std::vector<PipelineFrame>& tracked,
                                                       std::int64_t timestamp_ns,
                                                       std::int64_t max_gap_ns);

}  // namespace strata::odometry
