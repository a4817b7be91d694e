#include "cli/odometry_summary.h"

#include <algorithm>
#include <cmath>

#include "cli/report_json.h"
#include "strata/core/error.h"

namespace strata::apps {
namespace {

std::vector<trajectory::StampedPose> trackedPoses(const std::vector<odometry::PipelineFrame>& tracked) {
  std::vector<trajectory::StampedPose> poses;
  for (const auto& f : tracked)
    poses.push_back({1e-9 * static_cast<double>(f.timestamp_ns), f.T_W_C});
  return poses;
}

std::optional<trajectory::TrajectoryError> evaluate(const std::vector<trajectory::StampedPose>& estimate,
                                              const std::vector<trajectory::StampedPose>& truth,
                                              trajectory::Alignment alignment) {
  try {
    return trajectory::evaluateTrajectory(estimate, truth, alignment);
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

Json errorJson(const std::optional<trajectory::TrajectoryError>& e) {
  return e ? parseJson(trajectory::trajectoryErrorJson(*e)) : Json(nullptr);
}

/// Seconds of a nanosecond stamp.
double nsToSeconds(std::int64_t ns) { return 1e-9 * static_cast<double>(ns); }

Json failureLogJson(const odometry::PipelineStats& st) {
  Json log = Json::array();
  for (const auto& [t_ns, reason] : st.failure_log) {
    Json j;
    j["t_s"] = nsToSeconds(t_ns);
    j["reason"] = reason;
    log.push_back(std::move(j));
  }
  return log;
}

Json skippedJson(const OdometryRun& run) {
  const odometry::PipelineStats& st = run.stats;
  Json j;
  j["imu_nonfinite"] = st.imu_nonfinite_skipped + run.reader.imu_nonfinite_skipped;
  j["imu_out_of_range"] = st.imu_out_of_range_skipped;
  j["imu_out_of_order"] = st.imu_out_of_order_skipped;
  j["imu_gaps"] = run.reader.imu_gaps;
  j["imu_missing_samples"] = run.reader.imu_missing_samples;
  j["missing_images"] = run.reader.missing_images;
  j["unpaired_frames"] = run.reader.unpaired_left + run.reader.unpaired_right;
  j["frames_out_of_order"] = st.frames_out_of_order_skipped;
  j["frames_without_imu"] = st.frames_without_imu_skipped;
  return j;
}

/// Rates are null (NaN) where their time is 0.
Json timingJson(const OdometryRun& run) {
  const odometry::PipelineStats& st = run.stats;
  const double processing_s = 1e-3 * (st.frontend_ms_total + st.backend_ms_total);
  const double frames = static_cast<double>(st.frames_processed);
  const double n = static_cast<double>(std::max<std::size_t>(1, st.frames_processed));
  Json j;
  j["wall_s"] = run.wall_s;
  j["image_load_s"] = run.image_load_s;
  j["cpu_s"] = run.cpu_s;
  j["frames_per_cpu_second"] = run.cpu_s > 0 ? frames / run.cpu_s : NAN;
  j["frontend_ms_per_frame"] = st.frontend_ms_total / n;
  j["backend_ms_per_frame"] = st.backend_ms_total / n;
  j["frames_per_second"] = processing_s > 0 ? frames / processing_s : NAN;
  j["frames_per_second_with_decoding"] = run.wall_s > 0 ? frames / run.wall_s : NAN;
  return j;
}

Json accuracyJson(const OdometryAccuracy& a) {
  Json j;
  j["gravity_error_first_deg"] = a.gravity_error_first_deg;
  j["gravity_error_max_deg"] = a.gravity_error_max_deg;
  j["drift_m"] = a.first ? Json(a.first->ate_max_m) : Json(nullptr);
  j["se3"] = errorJson(a.se3);
  j["sim3"] = errorJson(a.sim3);
  j["first_pose"] = errorJson(a.first);
  return j;
}

}  // namespace

std::vector<trajectory::StampedPose> cameraTruth(const euroc::EurocDataset& dataset) {
  const Eigen::Isometry3d T_B_C0 = dataset.calibration().cameras.at(0).T_B_C;
  std::vector<trajectory::StampedPose> truth;
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
  a.se3 = evaluate(estimate, truth, trajectory::Alignment::kSE3);
  a.sim3 = evaluate(estimate, truth, trajectory::Alignment::kSim3);
  a.first = evaluate(estimate, truth, trajectory::Alignment::kFirstPose);
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
  Json j;
  j["session"] = run.session_dir;
  j["mode"] = "vio";
  j["stereo"] = run.stereo;
  j["frames_in_dataset"] = run.frames_in_dataset;
  j["frames_processed"] = st.frames_processed;
  j["frames_tracked"] = st.frames_tracking;
  j["frames_initializing"] = st.frames_initializing;
  j["failures"] = st.failures;
  j["reanchored_dead_reckoned"] = st.reanchored_dead_reckoned;
  j["reanchored_position_held"] = st.reanchored_position_held;
  j["first_tracked_s"] =
      st.first_tracking_ns >= 0 ? Json(nsToSeconds(st.first_tracking_ns)) : Json(nullptr);
  j["failure_log"] = failureLogJson(st);
  j["skipped"] = skippedJson(run);
  j["timing"] = timingJson(run);
  j["accuracy"] = run.accuracy ? accuracyJson(*run.accuracy) : Json(nullptr);
  return jsonFileText(j);
}

}  // namespace strata::apps
