#include "odometry/frontend/corner_detector.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>

#include "core/error.h"

namespace strata::odometry {
namespace {

int cellOf(const cv::Point2f& p, cv::Size size, const DetectorConfig& config) {
  const int col = std::clamp(static_cast<int>(p.x * config.grid_cols / size.width), 0,
                             config.grid_cols - 1);
  const int row = std::clamp(static_cast<int>(p.y * config.grid_rows / size.height), 0,
                             config.grid_rows - 1);
  return row * config.grid_cols + col;
}

cv::Mat freeMask(cv::Size size, const std::vector<cv::Point2f>& existing,
                 const DetectorConfig& config) {
  cv::Mat mask(size, CV_8UC1, cv::Scalar(0));
  const int b = config.border_px;
  mask(cv::Rect(b, b, size.width - 2 * b, size.height - 2 * b)).setTo(255);
  const int radius = static_cast<int>(std::ceil(config.min_distance_px));
  for (const cv::Point2f& p : existing) {
    cv::circle(mask, cv::Point(cvRound(p.x), cvRound(p.y)), radius, cv::Scalar(0), cv::FILLED);
  }
  return mask;
}

}  // namespace

void DetectorConfig::validate() const {
  if (target_features < 1) throw InputError("DetectorConfig: target_features must be >= 1");
  if (!(min_distance_px >= 1.0)) throw InputError("DetectorConfig: min_distance_px must be >= 1");
  if (!(quality_level > 0.0 && quality_level < 1.0)) {
    throw InputError("DetectorConfig: quality_level must be in (0, 1)");
  }
  if (grid_cols < 1 || grid_rows < 1) throw InputError("DetectorConfig: grid must be >= 1 x 1");
  if (border_px < 0) throw InputError("DetectorConfig: border_px must be >= 0");
}

std::vector<cv::Point2f> detectCorners(const cv::Mat& image,
                                       const std::vector<cv::Point2f>& existing, int wanted,
                                       const DetectorConfig& config) {
  std::vector<cv::Point2f> chosen;
  const cv::Size size = image.size();
  if (wanted <= 0 || size.width <= 2 * config.border_px || size.height <= 2 * config.border_px) {
    return chosen;
  }
  // Candidates already min_distance apart and away from existing tracks, strongest first; a few
  // times the wanted number so the grid pass has choice.
  std::vector<cv::Point2f> candidates;
  cv::goodFeaturesToTrack(image, candidates, 3 * wanted, config.quality_level,
                          config.min_distance_px, freeMask(size, existing, config), 3, false);
  const int cells = config.grid_cols * config.grid_rows;
  const int quota = std::max(1, (config.target_features + cells - 1) / cells);
  std::vector<int> per_cell(cells, 0);
  for (const cv::Point2f& p : existing) ++per_cell[cellOf(p, size, config)];
  std::vector<bool> taken(candidates.size(), false);
  // Pass 1 respects the quota; pass 2 fills what is left with the strongest remaining corners.
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t i = 0; i < candidates.size() && static_cast<int>(chosen.size()) < wanted;
         ++i) {
      if (taken[i]) continue;
      int& count = per_cell[cellOf(candidates[i], size, config)];
      if (pass == 0 && count >= quota) continue;
      ++count;
      taken[i] = true;
      chosen.push_back(candidates[i]);
    }
  }
  return chosen;
}

}  // namespace strata::odometry
