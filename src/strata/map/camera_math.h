#pragma once
// Host mirror of shaders/common/camera.glsl, used by the C++ reference kernels. Float throughout,
// in the same order of operations as the shaders, so reference and device agree to rounding.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

#include "strata/core/types.h"

namespace strata {

/// Camera parameters of one frame, in the float form the kernels use.
struct FrameCamera {
  Eigen::Vector4f K;  // fx, fy, cx, cy
  int width_px = 0;
  int height_px = 0;
  Eigen::Matrix4f T_W_C = Eigen::Matrix4f::Identity();
  Eigen::Matrix4f T_C_W = Eigen::Matrix4f::Identity();

  static FrameCamera from(const CameraIntrinsics& intrinsics, const Eigen::Isometry3d& T_W_C);
};

inline FrameCamera FrameCamera::from(const CameraIntrinsics& in, const Eigen::Isometry3d& T_W_C) {
  FrameCamera camera;
  camera.K = Eigen::Vector4f(in.fx_px, in.fy_px, in.cx_px, in.cy_px);
  camera.width_px = in.width_px;
  camera.height_px = in.height_px;
  camera.T_W_C = T_W_C.matrix().cast<float>();
  camera.T_C_W = T_W_C.inverse().matrix().cast<float>();
  return camera;
}

inline Eigen::Vector3f pixelRay(float u, float v, const Eigen::Vector4f& K) {
  return Eigen::Vector3f((u - K[2]) / K[0], (v - K[3]) / K[1], 1.0f);
}

inline bool depthValid(float depth_m, float min_depth_m, float max_depth_m) {
  return depth_m >= min_depth_m && depth_m <= max_depth_m;
}

}  // namespace strata
