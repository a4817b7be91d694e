#pragma once
// Odometry fused with localisations: the odometry (VIO or RGB-D tracking, frame O) gives smooth
// relative motion; localisations against the prior map (localizer.h) correct its drift. The
// state is the correction T_W_O (odometry frame to map frame) with a 6x6 covariance, a Kalman
// filter on SE(3): the correction's perturbation is a rotation about the current camera centre
// then a translation, in map axes (t, r), so that a yaw drift does not look like a large
// translation far from the origin. Between localisations the covariance grows with the distance
// flown (the odometry's drift per metre); moving the centre from p to p' transports it
// (d t = d t + d r x (p' - p)).
// Robustness: the first correction needs `init_agreeing` localisations that agree with each other
// through the odometry (a single wrong one cannot initialise); afterwards a localisation whose
// innovation's Mahalanobis distance exceeds the gate is rejected (counted, reason given). Output:
// T_W_C = T_W_O * T_O_C at every odometry pose; an accepted update moves it by K * innovation,
// which the gate bounds to sqrt(gate) times the correction's standard deviation.
// Frames: W map, O odometry, C camera; metres, radians, seconds.
// Thread safety: none (one owner).
#include <Eigen/Geometry>
#include <deque>
#include <optional>
#include <string>

#include "strata/localize/localizer.h"

namespace strata::localize {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

struct FusionConfig {
  /// Odometry drift: variance per metre flown of each translation axis (m^2/m) and of each
  /// rotation axis (rad^2/m); plus a floor per second for a robot that hovers.
  double translation_variance_per_m = 0.02 * 0.02;
  double rotation_variance_per_m = 0.005 * 0.005;
  double translation_variance_per_s = 0.001 * 0.001;
  double rotation_variance_per_s = 0.0005 * 0.0005;
  /// Chi-square gate of an innovation (6 degrees of freedom; 22.46: 99.9 %).
  double gate_chi2 = 22.46;
  /// Localisations needed to initialise, agreeing within init_max_disagreement_m / _rad after
  /// the odometry between them.
  int init_agreeing = 2;
  double init_max_disagreement_m = 0.2;
  double init_max_disagreement_rad = 0.1;
  /// Localisations are not trusted beyond this (their stated covariance is floored: sigma of
  /// at least this, m and rad): dense ICP's own figure is far too sure of itself.
  double min_localization_sigma_m = 0.03;
  double min_localization_sigma_rad = 0.02;
  /// Consecutive rejections after which the filter re-initialises (the correction itself is
  /// wrong, e.g. after a long gap in odometry).
  int reset_after_rejections = 8;
  void validate() const;
};

enum class FusionStatus {
  kUninitialised,  // no pose in the map frame yet
  kTracking,       // odometry with the last correction
  kCorrected,      // a localisation was accepted at this frame
};
const char* fusionStatusName(FusionStatus status);  // "uninitialised", "tracking", "corrected"

struct FusedPose {
  FusionStatus status = FusionStatus::kUninitialised;
  Eigen::Isometry3d T_W_C = Eigen::Isometry3d::Identity();  // valid unless kUninitialised
  Matrix6d covariance = Matrix6d::Zero();  // of the correction, (t, r) about the camera centre
  double translation_sigma_m = 0.0;        // sqrt of the largest translation eigenvalue
  double jump_m = 0.0;                     // how far this frame's update moved the camera
  std::string note;                        // e.g. why a localisation was rejected
};

class PoseFusion {
 public:
  explicit PoseFusion(const FusionConfig& config = {});

  /// A new odometry pose (T_O_C at timestamp_s). Time going backwards or a non-finite pose:
  /// InputError (nothing changes). Returns the map-frame pose with only the odometry applied.
  FusedPose predict(double timestamp_s, const Eigen::Isometry3d& T_O_C);
  /// A localisation of the frame last given to predict(); returns the fused pose of that frame.
  /// Refused localisations (not localised, gated out) leave the correction as it was.
  FusedPose correct(const Localization& localization);
  /// Forgets the correction (e.g. after the odometry restarted in a new frame).
  void reset();

  bool initialised() const { return initialised_; }
  /// The prior for the localiser at the last predicted frame, when initialised.
  std::optional<PosePrior> prior() const;
  const Eigen::Isometry3d& T_W_O() const { return T_W_O_; }
  std::size_t accepted() const { return accepted_; }
  std::size_t rejected() const { return rejected_; }

 private:
  FusedPose current(FusionStatus status) const;
  bool tryInitialise(const Localization& localization, std::string& note);

  FusionConfig config_;
  bool initialised_ = false;
  Eigen::Isometry3d T_W_O_ = Eigen::Isometry3d::Identity();
  Matrix6d P_ = Matrix6d::Zero();
  bool have_odometry_ = false;
  double last_time_s_ = 0.0;
  Eigen::Isometry3d T_O_C_ = Eigen::Isometry3d::Identity();
  // Initialisation candidates: (T_W_O implied by a localisation).
  std::deque<Eigen::Isometry3d> init_candidates_;
  std::size_t accepted_ = 0, rejected_ = 0;
  int rejections_in_a_row_ = 0;
};

}  // namespace strata::localize
