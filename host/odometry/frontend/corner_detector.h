#pragma once
// New corners where tracks are sparse: Shi-Tomasi (minimum eigenvalue) corners away from every
// existing track by min_distance_px, spread over a grid so that one textured region cannot take
// the whole budget (an even spread constrains rotation and translation better).
#include <opencv2/core.hpp>
#include <vector>

namespace strata::odometry {

struct DetectorConfig {
  int target_features = 180;     // tracks the front end keeps alive; more = slower, more robust
  double min_distance_px = 20.0; // between any two features (new or tracked)
  double quality_level = 0.01;   // Shi-Tomasi: fraction of the strongest corner's score
  int grid_cols = 8;             // the image is split into grid_cols x grid_rows cells with an
  int grid_rows = 5;             //   equal quota each
  int border_px = 8;             // no corners this close to the edge (KLT window support)

  /// Throws InputError naming the bad field.
  void validate() const;
};

/// Up to `wanted` new corners in `image` (8-bit grey), none within min_distance_px of `existing`
/// or of each other, at most a cell's quota per grid cell (quota = target / cells, counting
/// existing features) before any cell gets more. Ordered by grid pass, then corner strength.
std::vector<cv::Point2f> detectCorners(const cv::Mat& image,
                                       const std::vector<cv::Point2f>& existing, int wanted,
                                       const DetectorConfig& config);

}  // namespace strata::odometry
