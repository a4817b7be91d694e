#include "strata/lcm/convert_pose.h"

#include <cmath>

#include "strata/core/error.h"

namespace strata::lcm_io {
namespace {

constexpr double kQuaternionNormTolerance = 1e-3;

bool allFinite(const double* values, int count) {
  for (int i = 0; i < count; ++i) {
    if (!std::isfinite(values[i])) return false;
  }
  return true;
}

}  // namespace

pose_t encodePose(const Eigen::Isometry3d& T_W_C, std::int64_t utime,
                  const std::string& parent_frame, const std::string& child_frame) {
  pose_t pose{};
  pose.utime = utime;
  pose.parent_frame = parent_frame;
  pose.child_frame = child_frame;
  const Eigen::Vector3d t = T_W_C.translation();
  const Eigen::Quaterniond q(T_W_C.rotation());
  for (int i = 0; i < 3; ++i) pose.position[i] = t[i];
  pose.orientation[0] = q.w();
  pose.orientation[1] = q.x();
  pose.orientation[2] = q.y();
  pose.orientation[3] = q.z();
  return pose;
}

Eigen::Isometry3d decodePose(const pose_t& pose) {
  if (!allFinite(pose.position, 3) || !allFinite(pose.orientation, 4)) {
    throw InputError("pose at utime " + std::to_string(pose.utime) +
                     ": non-finite position or orientation");
  }
  Eigen::Quaterniond q(pose.orientation[0], pose.orientation[1], pose.orientation[2],
                       pose.orientation[3]);
  if (std::abs(q.norm() - 1.0) > kQuaternionNormTolerance) {
    throw InputError("pose at utime " + std::to_string(pose.utime) + ": quaternion norm " +
                     std::to_string(q.norm()) + " is not 1 (w, x, y, z expected)");
  }
  q.normalize();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.toRotationMatrix();
  T.translation() = Eigen::Vector3d(pose.position[0], pose.position[1], pose.position[2]);
  return T;
}

camera_info_t encodeCameraInfo(const CameraIntrinsics& intrinsics, const std::string& camera_id,
                               std::int64_t utime) {
  camera_info_t info{};
  info.utime = utime;
  info.camera_id = camera_id;
  info.width = intrinsics.width_px;
  info.height = intrinsics.height_px;
  info.fx = intrinsics.fx_px;
  info.fy = intrinsics.fy_px;
  info.cx = intrinsics.cx_px;
  info.cy = intrinsics.cy_px;
  info.distortion_model = "none";
  info.num_distortion = 0;
  return info;
}

CameraIntrinsics decodeCameraInfo(const camera_info_t& info) {
  const std::string what = "camera_info '" + info.camera_id + "'";
  if (info.num_distortion < 0 ||
      static_cast<std::size_t>(info.num_distortion) != info.distortion.size()) {
    throw InputError(what + ": num_distortion " + std::to_string(info.num_distortion) +
                     " disagrees with the coefficients sent");
  }
  if (info.distortion_model == "plumb_bob") {
    if (info.num_distortion != 5) throw InputError(what + ": plumb_bob needs 5 coefficients");
  } else if (info.distortion_model != "none" && !info.distortion_model.empty()) {
    throw InputError(what + ": unknown distortion model '" + info.distortion_model +
                     "' (none or plumb_bob)");
  }
  for (double k : info.distortion) {
    if (k != 0.0) {
      throw InputError(what +
                       ": non-zero distortion; send rectified images and zero "
                       "coefficients (Strata does not undistort)");
    }
  }
  CameraIntrinsics intrinsics;
  intrinsics.width_px = info.width;
  intrinsics.height_px = info.height;
  intrinsics.fx_px = static_cast<float>(info.fx);
  intrinsics.fy_px = static_cast<float>(info.fy);
  intrinsics.cx_px = static_cast<float>(info.cx);
  intrinsics.cy_px = static_cast<float>(info.cy);
  try {
    intrinsics.validate();
  } catch (const InputError& e) {
    throw InputError(what + ": " + e.what());
  }
  return intrinsics;
}

}  // namespace strata::lcm_io
