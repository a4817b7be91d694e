#pragma once
// The frame an odometry reports in: a visual(-inertial) odometry starts its own frame S where it
// is switched on, so two recordings of one place disagree by a rigid offset T_W_S before any
// drift. The frame is gravity-aligned (gravity makes roll and pitch observable to a VIO): the
// offset is a yaw and a translation only.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace strata::sim {

struct OdometryFrameConfig {
  /// The frame's origin is uniform in [-h, h] along world x and y. 5 m: a room or two apart.
  double horizontal_offset_m = 5.0;
  /// ... and in [-v, v] along world z (a VIO's start height differs little between recordings).
  double vertical_offset_m = 0.5;

  /// Throws InputError naming the first bad field.
  void validate() const;
};

/// T_W_S, the odometry frame in the world: yaw about world z uniform in [-pi, pi], translation
/// uniform in the box above, no roll or pitch. Draws from its own sub-stream of `seed`, so the
/// seed may be the one addOdometryDrift uses. Same seed, same frame.
Eigen::Isometry3d randomOdometryFrame(const OdometryFrameConfig& config, std::uint64_t seed);

/// The poses T_W_C expressed in frame S: T_S_C = T_S_W * T_W_C, one per pose.
std::vector<Eigen::Isometry3d> posesInFrame(const Eigen::Isometry3d& T_S_W,
                                            const std::vector<Eigen::Isometry3d>& T_W_C);

}  // namespace strata::sim
