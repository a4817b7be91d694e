#pragma once
// Calibrated cameras of the visual front end: pinhole intrinsics with lens distortion
// (radial-tangential k1 k2 p1 p2, as EuRoC/Kalibr "radtan", or equidistant k1..k4, as Kalibr
// "equidistant" / OpenCV fisheye) and the extrinsics of a stereo pair.
// NOTE: io/camera_model.h describes a depth camera (pinhole + depth PNG encoding, no distortion);
// this header reuses its CameraIntrinsics type and adds distortion and extrinsics rather than
// growing that struct, which the RGB-D readers and the engine share.
// Conventions: pixel (u, v) is the centre of column u, row v; camera frame x right, y down, z
// forward; "normalized" coordinates are undistorted (x / z, y / z).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>

#include "strata/core/types.h"

namespace strata::odometry {

enum class DistortionModel { kNone, kRadialTangential, kEquidistant };

/// One camera. Thread safety: const methods may be called from several threads at once.
struct Camera {
  int width_px = 752;
  int height_px = 480;
  double fx_px = 458.654, fy_px = 457.296, cx_px = 367.215, cy_px = 248.375;
  DistortionModel distortion = DistortionModel::kNone;
  /// radtan: k1 k2 p1 p2; equidistant: k1 k2 k3 k4; unused for kNone.
  std::array<double, 4> coefficients{0.0, 0.0, 0.0, 0.0};
  /// Camera-to-body extrinsics (EuRoC's T_BS of the camera's sensor.yaml).
  Eigen::Isometry3d T_B_C = Eigen::Isometry3d::Identity();
  /// Name for messages ("cam0", a file name...).
  std::string name = "camera";

  /// An undistorted camera with the core intrinsics (e.g. the simulator's grey camera).
  static Camera fromIntrinsics(const CameraIntrinsics& intrinsics, const std::string& name);

  /// Throws InputError naming `name` and the bad field (size, focal length, coefficients, a
  /// T_B_C whose rotation is not orthonormal).
  void validate() const;

  /// Normalized (undistorted) coordinates -> pixel. Exact formula of the distortion model.
  Eigen::Vector2d project(const Eigen::Vector2d& xy_norm) const;
  /// Camera-frame point -> pixel; z must be > 0 (not checked).
  Eigen::Vector2d projectPoint(const Eigen::Vector3d& p_C) const;
  /// Pixel -> normalized coordinates: the inverse of project() by Newton's method (converges to
  /// ~1e-12 over the image for the distortions of real lenses; EuRoC's k1 = -0.28 included).
  Eigen::Vector2d undistort(const Eigen::Vector2d& uv_px) const;
  /// Mean focal length: pixels per normalized unit, to turn pixel thresholds into normalized ones.
  double focalMean() const { return 0.5 * (fx_px + fy_px); }
  bool contains(const Eigen::Vector2d& uv_px, double border_px = 0.0) const;
};

/// A stereo pair: left = camera 0 (the reference of every observation), right = camera 1.
struct StereoCamera {
  Camera left;
  Camera right;

  /// Right-camera-to-left-camera transform from the two T_B_C: T_C0_C1 = T_B_C0^-1 T_B_C1.
  Eigen::Isometry3d T_C0_C1() const { return left.T_B_C.inverse() * right.T_B_C; }
  /// |t_C0_C1|, metres.
  double baseline_m() const { return T_C0_C1().translation().norm(); }
  /// Essential matrix E with x_right^T E x_left = 0 for normalized coordinates.
  Eigen::Matrix3d essentialRightLeft() const;

  /// Both cameras valid and the baseline > 1 mm; throws InputError naming the problem.
  void validate() const;
};

/// The camera's rotation between two frames from the body's (IMU preintegration gives
/// R_Bk_Bkm1): R_Ck_Ckm1 = R_C_B R_Bk_Bkm1 R_B_C, the prediction FeatureTracker::process takes.
inline Eigen::Matrix3d cameraRotation(const Eigen::Matrix3d& R_Bk_Bkm1,
                                      const Eigen::Isometry3d& T_B_C) {
  return T_B_C.linear().transpose() * R_Bk_Bkm1 * T_B_C.linear();
}

}  // namespace strata::odometry
