#pragma once
// The cameras of the visual-inertial rig: a left pinhole camera and an optional right one, both
// rigidly mounted on the IMU body B. Observations are in pixels of the undistorted images.
#include <Eigen/Geometry>
#include <optional>

namespace strata::odometry {

struct PinholeIntrinsics {
  double fx_px = 458.0;
  double fy_px = 458.0;
  double cx_px = 376.0;
  double cy_px = 240.0;
  int width_px = 752;
  int height_px = 480;

  Eigen::Vector2d project(const Eigen::Vector3d& p_C) const {
    return {fx_px * p_C.x() / p_C.z() + cx_px, fy_px * p_C.y() / p_C.z() + cy_px};
  }
  /// Pixel of the normalized coordinates (x / z, y / z).
  Eigen::Vector2d toPixel(const Eigen::Vector2d& xy) const {
    return {fx_px * xy.x() + cx_px, fy_px * xy.y() + cy_px};
  }
  /// Ray through pixel uv with z = 1.
  Eigen::Vector3d unproject(const Eigen::Vector2d& uv) const {
    return {(uv.x() - cx_px) / fx_px, (uv.y() - cy_px) / fy_px, 1.0};
  }
};

struct CameraRig {
  PinholeIntrinsics left;
  /// Pose of the left camera in the body (IMU) frame; fixed, given by calibration.
  Eigen::Isometry3d T_B_Cl = Eigen::Isometry3d::Identity();
  /// Set for a stereo rig.
  std::optional<PinholeIntrinsics> right;
  Eigen::Isometry3d T_B_Cr = Eigen::Isometry3d::Identity();

  /// Throws InputError naming the first bad field (non-positive focal length or image size,
  /// non-rigid extrinsics).
  void validate() const;
};

}  // namespace strata::odometry
