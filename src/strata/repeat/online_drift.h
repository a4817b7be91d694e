#pragma once
// Odometry drift applied online, one true pose at a time: the random walk of
// sim::addOdometryDrift (translation per axis and yaw about the vertical through the current true
// position, variances sigma^2 per metre travelled), for a closed loop whose next true pose depends
// on the estimate, so that the whole trajectory is not known in advance.
// Frames: the odometry frame O is the world frame at the first pose (the first pose is exact).
// Metres, radians. Thread safety: none (one owner).
#include <Eigen/Geometry>
#include <cstdint>

#include "strata/sim/rng.h"
#include "strata/sim/sensors/odometry_drift.h"

namespace strata::repeat {

class OnlineDrift {
 public:
  /// InputError for a bad config (DriftConfig::validate).
  OnlineDrift(const sim::DriftConfig& config, std::uint64_t seed);

  /// The odometry's T_O_C for the next true camera pose T_W_C.
  Eigen::Isometry3d next(const Eigen::Isometry3d& T_W_C);
  /// Distance travelled so far (metres).
  double distance_m() const { return distance_m_; }

 private:
  sim::DriftConfig config_;
  sim::Rng rng_;
  Eigen::Isometry3d D_ = Eigen::Isometry3d::Identity();  // E_1 o ... o E_k
  bool first_ = true;
  Eigen::Vector3d last_p_W_ = Eigen::Vector3d::Zero();
  double distance_m_ = 0.0;
};

}  // namespace strata::repeat
