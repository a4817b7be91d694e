#include "cli/odometry_summary.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/json_text.h"

namespace strata::apps {
namespace {

std::vector<traj::StampedPose> trackedPoses(const std::vector<odometry::PipelineFrame>& tracked) {
  std::vector<traj::StampedPose> poses;
  for (const auto& f : tracked)
    poses.push_back({1e-9 * static_cast<double>(f.timestamp_ns), f.T_W_C});
  return poses;
}

std::optional<traj::TrajectoryError> evaluate(const std::vector<traj::StampedPose>& estimate,
                                              const std::vector<traj::StampedPose>& truth,
                                              traj::Alignment alignment) {
  try {
    return traj::evaluateTrajectory(estimate, truth, alignment);
  } catch (const InputError&) {
    return std::nullopt;  // degenerate alignment (standstill) or no match
  }
}

// Angle between the gravity directions the two body rotations imply (world z in the body).
double gravityAngleDeg(const Eigen::Matrix3d& R_W_B_estimate, const Eigen::Matrix3d& R_W_B_truth) {
  const Eigen::Vector3d a = R_W_B_estimate.transpose() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d b = R_W_B_truth.transpose() * Eigen::Vector3d::UnitZ();
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI;
}

void appendError(std::ostringstream& s, const char* key,
                 const std::optional<traj::TrajectoryError>& e) {
  s << ", \"" << key << "\": " << (e ? traj::trajectoryErrorJson(*e) : std::string("null"));
}

}  // namespace

std::vector<traj::StampedPose> cameraTruth(const euroc::EurocDataset& dataset) {
  const Eigen::Isometry3d T_B_C0 = dataset.calibration().cameras.at(0).T_B_C;
  std::vector<traj::StampedPose> truth;
  for (const auto& state : dataset.groundTruth()) {
    truth.push_back({1e-9 * static_cast<double>(state.timestamp_ns), state.T_W_B * T_B_C0});
  }
  return truth;
}

std::optional<OdometryAccuracy> evaluateOdometry(
    const euroc::EurocDataset& dataset, const std::vector<odometry::PipelineFrame>& tracked) {
  if (dataset.groundTruth().empty() || tracked.empty()) return std::nullopt;
  const auto truth = cameraTruth(dataset);
  const auto estimate = trackedPoses(tracked);
  OdometryAccuracy a;
  a.se3 = evaluate(estimate, truth, traj::Alignment::kSE3);
  a.sim3 = evaluate(estimate, truth, traj::Alignment::kSim3);
  a.first = evaluate(estimate, truth, traj::Alignment::kFirstPose);
  if (!a.se3 && !a.first) return std::nullopt;
  bool first = true;
  for (const auto& f : tracked) {
    const auto T_W_B = euroc::interpolateGroundTruth(dataset.groundTruth(), f.timestamp_ns);
    if (!T_W_B) continue;
    const double angle = gravityAngleDeg(f.T_W_B.linear(), T_W_B->linear());
    if (first) a.gravity_error_first_deg = angle;
    a.gravity_error_max_deg = first ? angle : std::max(a.gravity_error_max_deg, angle);
    first = false;
  }
  return a;
}

std::string odometrySummaryJson(const OdometryRun& run) {
  const odometry::PipelineStats& st = run.stats;
  const double processing_s = 1e-3 * (st.frontend_ms_total + st.backend_ms_total);
  std::ostringstream s;
  s << "{\"session\": " << jsonQuoted(run.session_dir)
    << ", \"mode\": \"vio\", \"stereo\": " << (run.stereo ? "true" : "false")
    << ", \"frames_in_dataset\": " << run.frames_in_dataset
    << ", \"frames_processed\": " << st.frames_processed
    << ", \"frames_tracked\": " << st.frames_tracking
    << ", \"frames_initializing\": " << st.frames_initializing << ", \"failures\": " << st.failures
    << ", \"reanchored_dead_reckoned\": " << st.reanchored_dead_reckoned
    << ", \"reanchored_position_held\": " << st.reanchored_position_held
    << ", \"first_tracked_s\": "
    << (st.first_tracking_ns >= 0 ? jsonNumber(1e-9 * static_cast<double>(st.first_tracking_ns))
                                  : std::string("null"))
    << ", \"failure_log\": [";
  for (std::size_t i = 0; i < st.failure_log.size(); ++i) {
    s << (i ? ", " : "")
      << "{\"t_s\": " << jsonNumber(1e-9 * static_cast<double>(st.failure_log[i].first))
      << ", \"reason\": " << jsonQuoted(st.failure_log[i].second) << "}";
  }
  s << "], \"skipped\": {\"imu_nonfinite\": "
    << st.imu_nonfinite_skipped + run.reader.imu_nonfinite_skipped
    << ", \"imu_out_of_order\": " << st.imu_out_of_order_skipped
    << ", \"imu_gaps\": " << run.reader.imu_gaps
    << ", \"imu_missing_samples\": " << run.reader.imu_missing_samples
    << ", \"missing_images\": " << run.reader.missing_images
    << ", \"unpaired_frames\": " << run.reader.unpaired_left + run.reader.unpaired_right
    << ", \"frames_out_of_order\": " << st.frames_out_of_order_skipped
    << ", \"frames_without_imu\": " << st.frames_without_imu_skipped << "}";
  const double n = static_cast<double>(std::max<std::size_t>(1, st.frames_processed));
  s << ", \"timing\": {\"wall_s\": " << jsonNumber(run.wall_s)
    << ", \"image_load_s\": " << jsonNumber(run.image_load_s)
    << ", \"cpu_s\": " << jsonNumber(run.cpu_s) << ", \"frames_per_cpu_second\": "
    << jsonNumber(run.cpu_s > 0 ? static_cast<double>(st.frames_processed) / run.cpu_s : NAN)
    << ", \"frontend_ms_per_frame\": " << jsonNumber(st.frontend_ms_total / n)
    << ", \"backend_ms_per_frame\": " << jsonNumber(st.backend_ms_total / n)
    << ", \"frames_per_second\": "
    << jsonNumber(processing_s > 0 ? static_cast<double>(st.frames_processed) / processing_s : NAN)
    << ", \"frames_per_second_with_decoding\": "
    << jsonNumber(run.wall_s > 0 ? static_cast<double>(st.frames_processed) / run.wall_s : NAN)
    << "}";
  s << ", \"accuracy\": ";
  if (!run.accuracy) {
    s << "null";
  } else {
    const OdometryAccuracy& a = *run.accuracy;
    s << "{\"gravity_error_first_deg\": " << jsonNumber(a.gravity_error_first_deg)
      << ", \"gravity_error_max_deg\": " << jsonNumber(a.gravity_error_max_deg)
      << ", \"drift_m\": " << (a.first ? jsonNumber(a.first->ate_max_m) : std::string("null"));
    appendError(s, "se3", a.se3);
    appendError(s, "sim3", a.sim3);
    appendError(s, "first_pose", a.first);
    s << "}";
  }
  s << "}\n";
  return s.str();
}

}  // namespace strata::apps
