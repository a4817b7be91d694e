#pragma once
// What `strata odometry` reports about a run: the pipeline's counters and timing, and, against
// the session's ground truth when it has one, the trajectory error (SE(3) and Sim(3) alignment,
// RPE), the drift from the first pose, and the gravity direction error at initialisation.
#include <optional>
#include <string>
#include <vector>

#include "strata/io/euroc_dataset.h"
#include "strata/odometry/pipeline/vio_pipeline.h"
#include "strata/trajectory/trajectory_error.h"

namespace strata::apps {

struct OdometryAccuracy {
  // Each nullopt where the alignment cannot be made (e.g. SE(3) of a standstill: all positions
  // in one point leave the rotation free).
  std::optional<trajectory::TrajectoryError> se3;    // the headline for stereo (metric) odometry
  std::optional<trajectory::TrajectoryError> sim3;   // for mono: the scale the IMU gave, checked
  std::optional<trajectory::TrajectoryError> first;  // aligned at the first pose: drift (ate_max_m)
  /// Angle between the estimated and the true gravity direction in the body frame, degrees: at
  /// the first tracked frame, and the largest over the run.
  double gravity_error_first_deg = 0.0;
  double gravity_error_max_deg = 0.0;
};

struct OdometryRun {
  std::string session_dir;
  bool stereo = true;
  std::size_t frames_in_dataset = 0;
  odometry::PipelineStats stats;
  euroc::ReaderStats reader;
  double wall_s = 0.0;        // the whole replay, image decoding included
  double image_load_s = 0.0;  // of which decoding PNGs
  double cpu_s = 0.0;         // CPU time of the process over the replay (all threads)
  std::vector<odometry::PipelineFrame> tracked;  // tracking frames, in time order
  std::optional<OdometryAccuracy> accuracy;      // with ground truth only
};

/// The truth of cam0 (T_W_B * T_B_C0 at every ground-truth state) as a TUM trajectory.
std::vector<trajectory::StampedPose> cameraTruth(const euroc::EurocDataset& dataset);

/// Errors of the tracked frames against the dataset's ground truth; nullopt without truth or
/// without a tracked frame that matches it.
std::optional<OdometryAccuracy> evaluateOdometry(
    const euroc::EurocDataset& dataset, const std::vector<odometry::PipelineFrame>& tracked);

/// The summary as JSON text.
std::string odometrySummaryJson(const OdometryRun& run);

}  // namespace strata::apps
