#pragma once
// What the visual front end hands the back end per frame: one observation per tracked feature.
// Shared by both sides of strata::odometry.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

namespace strata::odometry {

/// One feature seen in one frame. Pixel coordinates (u right, v down, pixel centres at integers) of
/// the undistorted image of each camera of the rig (camera_rig.h); no rectification is assumed.
struct FeatureObservation {
  /// Same id in every frame that sees the same scene point; never reused for another point.
  std::uint64_t track_id = 0;
  Eigen::Vector2d uv_left = Eigen::Vector2d::Zero();
  /// Set when the point was matched in the right camera of a stereo rig.
  std::optional<Eigen::Vector2d> uv_right;
};

/// All observations of one camera frame (left and right images exposed at t_s).
struct FrameObservations {
  double t_s = 0.0;  // same clock as the IMU samples
  std::vector<FeatureObservation> features;
};

}  // namespace strata::odometry
