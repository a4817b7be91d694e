#pragma once
// Accuracy of an estimated camera trajectory against the truth: poses associated by timestamp,
// aligned (trajectory_alignment.h), then the absolute trajectory error (ATE: position error after
// alignment) and the relative pose error per metre travelled (RPE: drift of the motion over
// segments of a fixed length along the true path, independent of the alignment's rotation and
// translation). The definitions follow the TUM RGB-D benchmark (Sturm et al., IROS 2012) with
// segments measured in metres as in KITTI (Geiger et al., CVPR 2012). Figures: docs/odometry.md.
#include <Eigen/Geometry>
#include <cstddef>
#include <string>
#include <vector>

#include "strata/io/tum_format.h"
#include "strata/trajectory/trajectory_alignment.h"

namespace strata::trajectory {

/// One pose of a trajectory: camera-to-world (T_W_C) at a time, like a line of groundtruth.txt.
using StampedPose = tum::TimedPose;

struct TrajectoryErrorOptions {
  Alignment alignment = Alignment::kSE3;
  /// An estimate pose is matched to the nearest truth pose within this many seconds; unmatched
  /// estimate poses are counted and left out.
  double max_time_difference_s = 0.02;
  /// RPE segment length along the true path, metres. Shorter paths give no RPE (NaN, 0 pairs).
  double rpe_segment_m = 1.0;
};

struct TrajectoryError {
  std::size_t estimated = 0;  // estimate poses given
  std::size_t matched = 0;    // of them, matched to a truth pose
  double duration_s = 0.0;    // first to last matched timestamp
  double path_length_m = 0.0; // along the matched truth positions
  Alignment alignment = Alignment::kSE3;
  SimilarityTransform aligned;  // truth-from-estimate transform that was applied
  double scale = 1.0;           // aligned.scale
  // ATE over the matched poses after alignment, metres.
  double ate_rmse_m = 0.0, ate_mean_m = 0.0, ate_median_m = 0.0, ate_max_m = 0.0;
  /// Orientation error after alignment (RMS angle of R_gt^T * R_aligned), degrees.
  double rotation_rmse_deg = 0.0;
  /// RPE over every segment starting at a matched pose and ending at the first pose at least
  /// rpe_segment_m further along the true path: RMS of |t_err| / length (percent) and of the
  /// rotation angle / length (degrees per metre). The estimate's motion is scaled by `scale`.
  std::size_t rpe_pairs = 0;
  double rpe_segment_m = 1.0;
  double rpe_trans_percent = 0.0;
  double rpe_rot_deg_per_m = 0.0;
  /// Per matched pose: timestamp, aligned estimate position, truth position, error (metres).
  std::vector<double> timestamps_s;
  std::vector<Eigen::Vector3d> estimate_positions_m, truth_positions_m;
  std::vector<double> position_errors_m;
};

/// Evaluates `estimate` against `truth` (both sorted by timestamp, as tum::readTrajectory
/// returns them). Throws InputError when no estimate pose matches a truth pose, when a pose is not
/// finite, or when the alignment cannot be made (alignTrajectory).
TrajectoryError evaluateTrajectory(const std::vector<StampedPose>& estimate,
                                   const std::vector<StampedPose>& truth,
                                   const TrajectoryErrorOptions& options = {});

/// The same with the alignment given directly (the signature the odometry code uses).
TrajectoryError evaluateTrajectory(const std::vector<StampedPose>& estimate,
                                   const std::vector<StampedPose>& truth, Alignment alignment,
                                   double max_time_difference_s = 0.02);

/// The figures as a JSON object indented by two spaces, no trailing newline (the per-pose arrays
/// left out); NaN is written as null.
std::string trajectoryErrorJson(const TrajectoryError& error);

/// Relative pose error over segments of `segment_m` along the truth (the positions of `truth`
/// index-matched to `estimate`), with the estimate's translations multiplied by `scale`.
/// Writes pairs, RMS translation error in percent of the segment and RMS rotation error in
/// degrees per metre; NaN for both with no pair.
void relativePoseError(const std::vector<Eigen::Isometry3d>& estimate,
                       const std::vector<Eigen::Isometry3d>& truth, double segment_m, double scale,
                       std::size_t* pairs, double* trans_percent, double* rot_deg_per_m);

}  // namespace strata::trajectory
