#pragma once
// New corners where tracks are sparse: FAST candidates (Rosten and Drummond 2006; far cheaper
// than a full Shi-Tomasi response, docs/odometry.md step 6) ranked by their Shi-Tomasi score
// (the smaller eigenvalue of the gradient structure tensor, which is what KLT needs to converge),
// away from every existing track by min_distance_px, spread over a grid so that one textured
// region cannot take the whole budget (an even spread constrains rotation and translation
// better).
#include <opencv2/core.hpp>
#include <vector>

namespace strata::odometry {

struct DetectorConfig {
  int target_features = 180;      // tracks the front end keeps alive; more = slower, more robust
  double min_distance_px = 20.0;  // between any two features (new or tracked)
  int fast_threshold = 20;      // FAST intensity step; a second round at half where it falls short
  double quality_level = 0.01;  // Shi-Tomasi score floor: fraction of the strongest candidate's
  int score_window_px = 7;      // side of the structure tensor window of the score
  int grid_cols = 8;            // the image is split into grid_cols x grid_rows cells with an
  int grid_rows = 5;            //   equal quota each
  int border_px = 8;            // no corners this close to the edge (KLT window support)

  /// Throws InputError naming the bad field.
  void validate() const;
};

/// Shi-Tomasi score at an integer pixel: smaller eigenvalue of the summed gradient products over
/// a window_px x window_px window (central differences, grey levels^2 per pixel^2 / window area);
/// 0 where the window leaves the image.
double shiTomasiScore(const cv::Mat& image, int u, int v, int window_px);

/// Up to `wanted` new corners in `image` (8-bit grey), none within min_distance_px of `existing`
/// or of each other, at most a cell's quota per grid cell (quota = target / cells, counting
/// existing features) before any cell gets more. Ordered by grid pass, then corner strength.
/// Positions are integer pixels (FAST); KLT refines them from the next frame on.
std::vector<cv::Point2f> detectCorners(const cv::Mat& image,
                                       const std::vector<cv::Point2f>& existing, int wanted,
                                       const DetectorConfig& config);

}  // namespace strata::odometry
