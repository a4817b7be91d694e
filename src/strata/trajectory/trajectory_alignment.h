#pragma once
// Alignment of an estimated trajectory to the truth before its error is measured: an estimate
// lives in its own world frame (the first frame defines it), so its positions are compared after
// the rigid (SE(3)) or similarity (Sim(3), for monocular estimates whose scale is unobservable)
// transform that fits them best, or after pinning the first pose (drift from the start).
#include <Eigen/Geometry>
#include <vector>

namespace strata::trajectory {

enum class Alignment {
  kNone,       // compare as given: both trajectories in the same world frame
  kFirstPose,  // T_gt_est = T_gt_0 * T_est_0^-1: the error is drift from the first pose
  kSE3,        // least-squares rotation + translation of the positions (Umeyama, no scale)
  kSim3,       // the same with a scale
};

/// "none", "first", "se3", "sim3"; throws InputError naming the text otherwise.
Alignment parseAlignment(const std::string& text);
const char* alignmentName(Alignment alignment);

/// p_gt ≈ scale * (R * p_est) + t, and for orientations R_gt ≈ R * R_est.
struct SimilarityTransform {
  Eigen::Isometry3d T_gt_est = Eigen::Isometry3d::Identity();  // rotation and translation
  double scale = 1.0;
  /// True when the rotation came from the orientations (a near-straight path, see below).
  bool rotation_from_orientations = false;

  Eigen::Vector3d apply(const Eigen::Vector3d& p_est) const;
  /// The pose in the truth's world: rotation T_gt_est.linear() * R, position apply(t).
  Eigen::Isometry3d apply(const Eigen::Isometry3d& T_est_C) const;
};

/// The transform of `alignment` taking matched estimate poses onto matched truth poses (same
/// length, index i of one matches index i of the other, at least one pair). kSE3 and kSim3 fit the
/// positions by Umeyama's closed form (Eigen::umeyama). Positions along a near-straight path
/// (second principal spread under 10 % of the first) leave the rotation about the path's axis to
/// noise, so there the rotation is the chordal mean of R_gt_i * R_est_i^T and only scale and
/// translation are fitted to the positions. Throws InputError for an empty or uneven input, and
/// for kSim3 when the estimate has no extent (all positions within 1 mm of their mean: scale
/// unobservable).
SimilarityTransform alignTrajectory(const std::vector<Eigen::Isometry3d>& estimate,
                                    const std::vector<Eigen::Isometry3d>& truth,
                                    Alignment alignment);

}  // namespace strata::trajectory
