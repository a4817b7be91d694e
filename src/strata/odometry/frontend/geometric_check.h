#pragma once
// Geometric outlier rejection of frame-to-frame correspondences, in normalized (undistorted)
// coordinates so lens distortion cannot bias it:
//   - parallax (rotation-compensated when a rotation prediction is given) at least
//     homography_below_parallax_px: RANSAC on the essential matrix (5-point, Nister 2004),
//     Sampson error below ransac_threshold_px;
//   - below: RANSAC on a homography, transfer error below ransac_threshold_px, as long as it
//     rejects at most max_homography_reject_share of the points (else E as above). An essential
//     matrix is undetermined when the camera barely translates (a still or only rotating camera:
//     every translation fits), so it would let a moving object through; a homography is exact
//     there. When small flow only hides translation (a rotation cancelling it and no prediction
//     given), H would reject good points at other depths: the share bound hands over to E.
// Both models are refit by least squares on RANSAC's inliers and the inliers recomputed from
// the refit (one minimal sample's noise otherwise drops good points near the bound).
#include <Eigen/Geometry>
#include <optional>
#include <vector>

namespace strata::odometry {

struct GeometricCheckConfig {
  double ransac_threshold_px = 1.0;  // inlier bound; lower drops more good tracks on noisy images
  double confidence = 0.999;         // RANSAC: probability of drawing one all-inlier sample
  double homography_below_parallax_px = 1.5;  // median parallax under which H is tried first
  double max_homography_reject_share = 0.15;  // H rejecting more: translation, use E
  int min_correspondences = 10;               // fewer: no check (everything is kept, model '-')

  /// Throws InputError naming the bad field.
  void validate() const;
};

struct GeometricCheckResult {
  std::vector<unsigned char> inlier;  // one per correspondence, 1 = kept
  char model = '-';                   // 'E', 'H' or '-' (not checked)
  double median_parallax_px = 0.0;    // the figure that chose the model
  int rejected = 0;
};

/// `xy_prev` and `xy_cur`: normalized coordinates of the same tracks in the previous and the
/// current frame. `R_cur_prev` (optional) rotates previous-frame bearing vectors into the current
/// frame and only serves to measure parallax. `focal_px` converts pixel thresholds.
GeometricCheckResult rejectOutliers(const std::vector<Eigen::Vector2d>& xy_prev,
                                    const std::vector<Eigen::Vector2d>& xy_cur,
                                    const std::optional<Eigen::Matrix3d>& R_cur_prev,
                                    double focal_px, const GeometricCheckConfig& config);

/// Parallax of one correspondence in pixels: |xy_cur - proj(R_cur_prev [xy_prev; 1])| * focal.
double rotationCompensatedParallaxPx(const Eigen::Vector2d& xy_prev, const Eigen::Vector2d& xy_cur,
                                     const std::optional<Eigen::Matrix3d>& R_cur_prev,
                                     double focal_px);

}  // namespace strata::odometry
