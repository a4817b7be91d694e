#pragma once
// Configuration and result of RGB-D tracking (rgbd_tracker.h). Units: metres, degrees, pixels.
// validate() throws InputError naming the field.
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

namespace strata {

struct TrackConfig {
  /// Pyramid levels of the live depth (level l has 2^-l the resolution). More levels widen the
  /// basin of convergence; each level costs one pass of iterations.
  int levels = 3;
  /// Gauss-Newton iterations per level, indexed by level: [0] the finest (size must equal
  /// `levels`); levels run coarsest first.
  std::vector<int> iterations{4, 5, 10};
  /// The model is raycast at the resolution of this pyramid level (0: the frame's; 1: half, a
  /// quarter of the rays). The raycast is the costliest step; every live level associates with it.
  int model_level = 1;
  /// The live depth is smoothed before the pyramid (bilateral filter, depth_filter.h): normals of
  /// raw depth are noise where the depth noise nears a pixel's footprint, and the normal gate then
  /// drops true matches. Spatial sigma in pixels (window ceil(2 sigma); 0: no smoothing) and range
  /// sigma as a share of the pixel's depth (larger steps are edges and stay sharp).
  float smoothing_sigma_px = 2.0f;
  float smoothing_depth_share = 0.02f;
  /// Pyramid: a coarse depth is the mean of the valid depths of its 2x2 block within this of the
  /// nearest one (mixing foreground and background would invent surfaces).
  float pyramid_depth_threshold_m = 0.05f;
  /// Projective data association: a live point pairs with the model pixel it projects to when
  /// they are closer than this and their normals differ by less than max_normal_angle_deg.
  float max_distance_m = 0.10f;
  float max_normal_angle_deg = 30.0f;
  /// Huber threshold on |r|: residuals beyond it are down-weighted by huber_m / |r| (0: plain
  /// least squares). About twice the depth noise.
  float huber_m = 0.01f;
  /// Weight of the photometric term (photometric.h) beside the point-to-plane one: an intensity
  /// residual (0..1) times this counts as a point-to-plane residual in metres. 0, or a frame
  /// without colour: geometry alone. 1 reaches the figures of docs/track.md (a SUN3D fragment
  /// whose geometry cannot tell a rotation from a sideways step drifted 99 mm without it, 13 mm
  /// with it).
  double color_weight = 1.0;
  /// The iterations of a level stop when the update is smaller than this (translation metres +
  /// rotation radians, 2-norm).
  double convergence_update = 1e-6;

  // Failure rules: a frame that breaks one is lost (and must not be fused).
  /// Inliers at the finest level over the valid live pixels of that level.
  double min_inlier_fraction = 0.2;
  /// Absolute minimum of inliers at the finest level.
  std::uint32_t min_inliers = 200;
  /// RMS of the inliers' residuals at the finest level.
  double max_rms_m = 0.03;
  /// Smallest eigenvalue of JᵀJ / inliers (J rows [n, p × n], camera frame, metres; with the
  /// photometric term its weighted rows too): below it geometry and texture together do not
  /// constrain all six degrees of freedom (a bare plane, a blank corridor).
  double min_eigenvalue = 1e-4;
  /// The stated uncertainty (TrackResult::covariance) is the Gauss-Newton covariance
  /// σ̂² (JᵀJ)⁻¹ times this variance factor. The raw figure treats every pixel's residual as
  /// independent; neighbouring pixels' are not, so it understates the error a frame adds about
  /// 32-fold in sigma (measured on the SUN3D study room's first fragment, median of the motion
  /// error from the previous frame over the raw sigma; held out: fragment 2 and redkitchen,
  /// docs/track.md). 1000 ≈ 32². Judges nothing: a figure for whoever uses the pose.
  double covariance_scale = 1000.0;
  /// Largest accepted difference between the result and the guess.
  double max_translation_jump_m = 0.2;
  double max_rotation_jump_deg = 20.0;

  void validate() const;
};

enum class TrackStatus : std::uint8_t { kOk = 0, kLost = 1 };

/// The outcome of one tracked frame.
struct TrackResult {
  TrackStatus status = TrackStatus::kLost;
  std::string reason;  // why the frame is lost ("" when ok)
  Eigen::Isometry3d T_W_C = Eigen::Isometry3d::Identity();  // estimate (the guess when lost early)
  std::uint32_t inliers = 0;         // finest level, last evaluation
  std::uint32_t valid_pixels = 0;    // live pixels with depth and normal at the finest level
  double inlier_fraction = 0.0;
  double rms_m = 0.0;                // inliers' residual RMS, finest level
  double min_eigenvalue = 0.0;       // of JᵀJ / inliers, finest level
  /// The stated uncertainty of the pose: covariance of ξ (translation m, rotation rad, camera
  /// frame; T_W_C exp(ξ)): the final system's Gauss-Newton covariance (gauss_newton.h
  /// poseCovariance) times TrackConfig::covariance_scale. The sigmas are the square roots of the
  /// largest eigenvalue of its translation and rotation blocks (the worst direction); infinite
  /// when the system is singular (such a frame is lost as ill-conditioned).
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
  double translation_sigma_m = 0.0;
  double rotation_sigma_deg = 0.0;
  int iterations = 0;                // over all levels
  double raycast_ms = 0.0;           // device time of the model raycast
  double equations_ms = 0.0;         // device time of the normal equations, summed
  double wall_ms = 0.0;              // whole track() call

  bool ok() const { return status == TrackStatus::kOk; }
};

}  // namespace strata
