#pragma once
// Dense point-to-plane ICP between two depth images with projective data association: b's
// pixels (subsampled) moved into camera a by T_a_b and projected into a's depth image, where a's
// vertex and normal (from neighbouring depths) give the plane. Gauss-Newton on a right
// perturbation T_a_b * Exp(delta), delta = (tx ty tz rx ry rz).
#include <Eigen/Geometry>

#include "strata/core/types.h"
#include "strata/store/store_types.h"

namespace strata::align::detail {

struct DenseIcpConfig {
  int iterations = 15;
  int stride_px = 4;
  double max_distance_m = 0.10;
  double max_normal_angle_rad = 0.5;
};

struct DenseIcpResult {
  bool converged = false;  // false: too few correspondences or a singular system
  Eigen::Isometry3d T_a_b = Eigen::Isometry3d::Identity();
  double rms_m = 0.0;                             // point-to-plane RMS of the final correspondences
  int inliers = 0;                                // final correspondences
  int valid_b = 0;                                // subsampled pixels of b with a depth
  store::Matrix6d JtJ = store::Matrix6d::Zero();  // of the final correspondences, unweighted
};

/// Sizes must match the intrinsics (the caller checks).
DenseIcpResult denseIcp(const DepthImage& depth_a, const CameraIntrinsics& intrinsics_a,
                        const DepthImage& depth_b, const CameraIntrinsics& intrinsics_b,
                        const Eigen::Isometry3d& T_a_b_initial, const DenseIcpConfig& config);

}  // namespace strata::align::detail
