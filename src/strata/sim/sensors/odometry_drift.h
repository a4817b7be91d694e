#pragma once
// Odometry drift: the poses a mapper would receive from visual(-inertial) odometry, made from the
// true poses by a random walk in translation and yaw per metre travelled. The truth stays with the
// caller. Roll and pitch do not drift (gravity makes them observable to VIO).
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace strata::sim {

struct DriftConfig {
  /// Translation random walk, per axis: sigma after d metres = sigma * sqrt(d). 0.01 = 1 cm after
  /// 1 m, ~3 cm after 10 m (the 1 % class of good VIO).
  double translation_sigma_m_per_sqrt_m = 0.01;
  /// Yaw random walk about world z: sigma after d metres = sigma * sqrt(d). 0.005 rad = 0.29 deg.
  double yaw_sigma_rad_per_sqrt_m = 0.005;

  /// Throws InputError naming the first bad field.
  void validate() const;
};

/// Drifted copies of the true camera-to-world poses. Step k adds errors with variances
/// sigma^2 * |p_k - p_{k-1}| (distance travelled): a translation offset, and a yaw rotation about
/// the vertical through the current true position, so the error rotates all later motion, as
/// odometry does: T'_k = E_1 o E_2 o ... o E_k o T_k. The first pose is exact. Same seed, same
/// poses.
std::vector<Eigen::Isometry3d> addOdometryDrift(const std::vector<Eigen::Isometry3d>& poses,
                                                const DriftConfig& config, std::uint64_t seed);

}  // namespace strata::sim
