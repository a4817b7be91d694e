#pragma once
// pose_t <-> T_W_C, camera_info_t <-> CameraIntrinsics, with the checks a mapper needs before it
// lets a pose or a calibration near the map.
#include <Eigen/Geometry>
#include <string>

#include "strata/core/types.h"
#include "strata/camera_info_t.hpp"
#include "strata/pose_t.hpp"

namespace strata::lcm_io {

inline constexpr const char* kWorldFrame = "world";
inline constexpr const char* kCameraFrame = "camera";

/// T_parent_child as pose_t (zero covariance: unknown).
pose_t encodePose(const Eigen::Isometry3d& T_W_C, std::int64_t utime,
                  const std::string& parent_frame = kWorldFrame,
                  const std::string& child_frame = kCameraFrame);

/// The transform of a pose. Throws InputError for non-finite entries or a quaternion whose norm is
/// not 1 within 1e-3 (garbage, not rounding); the quaternion is normalised.
Eigen::Isometry3d decodePose(const pose_t& pose);

/// Intrinsics as camera_info_t without distortion ("none").
camera_info_t encodeCameraInfo(const CameraIntrinsics& intrinsics, const std::string& camera_id,
                               std::int64_t utime);

/// Throws InputError for bad sizes/focal lengths (CameraIntrinsics::validate), an unknown
/// distortion model, a coefficient count that disagrees with it, or non-zero distortion (Strata
/// fuses rectified images).
CameraIntrinsics decodeCameraInfo(const camera_info_t& info);

}  // namespace strata::lcm_io
