#pragma once
// Left-to-right stereo matching by KLT: each left feature is tracked into the right image from a
// guess (its last right position moved by its left motion, else the projection at
// init_depth_m; new ones missed are tried again from retry_depth_m), checked forward-backward,
// against the epipolar line of the calibrated pair (for a rectified pair: the same row) and against
// depth bounds by triangulation.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "strata/odometry/frontend/camera.h"
#include "strata/odometry/frontend/klt.h"

namespace strata::odometry {

struct StereoMatchConfig {
  double epipolar_max_px = 1.5;  // distance to the epipolar line in the right image
  double min_depth_m = 0.1;      // triangulated depth in both cameras must lie in the bounds
  double max_depth_m = 60.0;     //   (positive disparity; far points constrain only rotation)
  double init_depth_m = 3.0;     // depth of the initial guess of a feature never matched before
  double retry_depth_m = 0.8;    // second guess for new features the first missed (0 = none)
  /// Scale and offset the right image to the left image's mean and spread before matching: KLT
  /// assumes constant brightness, and the two eyes' exposures differ (EuRoC: ~15 grey levels).
  bool match_brightness = true;

  /// Throws InputError naming the bad field.
  void validate() const;
};

struct StereoMatch {
  Eigen::Vector2d uv_right_px;
  Eigen::Vector2d xy_right_norm;
  double depth_left_m;  // triangulated z in the left camera
};

/// Depths (z_left, z_right) of the two rays' closest approach, least squares; nullopt when the
/// rays are parallel. xy_*: normalized coordinates; T_C1_C0 maps left-camera points to right.
std::optional<Eigen::Vector2d> triangulateDepths(const Eigen::Vector2d& xy_left,
                                                 const Eigen::Vector2d& xy_right,
                                                 const Eigen::Isometry3d& T_C1_C0);

/// One result per left feature (nullopt = rejected). `retry_near[i]`: try again from
/// retry_depth_m if the first guess misses (the tracker sets it for new tracks only: a track
/// missed then is mostly occluded in the right eye, and retrying it every frame costs a second
/// KLT pass). `guess_right_px[i]` (optional) overrides
/// the projection guess.
std::vector<std::optional<StereoMatch>> matchStereo(
    const std::vector<cv::Mat>& pyramid_left, const std::vector<cv::Mat>& pyramid_right,
    const StereoCamera& camera, const std::vector<Eigen::Vector2d>& uv_left_px,
    const std::vector<Eigen::Vector2d>& xy_left_norm,
    const std::vector<std::optional<Eigen::Vector2d>>& guess_right_px,
    const std::vector<bool>& retry_near, const KltConfig& klt, double border_px,
    const StereoMatchConfig& config);

}  // namespace strata::odometry
