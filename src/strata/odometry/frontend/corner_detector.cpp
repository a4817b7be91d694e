#include "strata/odometry/frontend/corner_detector.h"

#include <algorithm>
#include <cmath>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "strata/core/error.h"

namespace strata::odometry {
namespace {

int cellOf(const cv::Point2f& p, cv::Size size, const DetectorConfig& config) {
  const int col =
      std::clamp(static_cast<int>(p.x * config.grid_cols / size.width), 0, config.grid_cols - 1);
  const int row =
      std::clamp(static_cast<int>(p.y * config.grid_rows / size.height), 0, config.grid_rows - 1);
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
  if (fast_threshold < 1 || fast_threshold > 255) {
    throw InputError("DetectorConfig: fast_threshold must be in [1, 255]");
  }
  if (score_window_px < 3 || score_window_px % 2 == 0) {
    throw InputError("DetectorConfig: score_window_px must be odd and >= 3");
  }
  if (!(quality_level > 0.0 && quality_level < 1.0)) {
    throw InputError("DetectorConfig: quality_level must be in (0, 1)");
  }
  if (grid_cols < 1 || grid_rows < 1) throw InputError("DetectorConfig: grid must be >= 1 x 1");
  if (border_px < 0) throw InputError("DetectorConfig: border_px must be >= 0");
}

double shiTomasiScore(const cv::Mat& image, int u, int v, int window_px) {
  const int h = window_px / 2;
  if (u - h - 1 < 0 || v - h - 1 < 0 || u + h + 1 >= image.cols || v + h + 1 >= image.rows) {
    return 0.0;
  }
  double xx = 0.0, xy = 0.0, yy = 0.0;
  for (int y = v - h; y <= v + h; ++y) {
    const std::uint8_t* row = image.ptr<std::uint8_t>(y);
    const std::uint8_t* up = image.ptr<std::uint8_t>(y - 1);
    const std::uint8_t* down = image.ptr<std::uint8_t>(y + 1);
    for (int x = u - h; x <= u + h; ++x) {
      const double gx = 0.5 * (row[x + 1] - row[x - 1]), gy = 0.5 * (down[x] - up[x]);
      xx += gx * gx;
      xy += gx * gy;
      yy += gy * gy;
    }
  }
  const double n = static_cast<double>(window_px * window_px);
  const double half_trace = 0.5 * (xx + yy) / n, half_diff = 0.5 * (xx - yy) / n;
  return half_trace - std::sqrt(half_diff * half_diff + (xy / n) * (xy / n));
}

namespace {

struct Candidate {
  cv::Point2f uv;
  double score;
};

// FAST corners inside the free mask, scored and sorted strongest first, floored by quality.
std::vector<Candidate> scoredCandidates(const cv::Mat& image, const cv::Mat& free, int threshold,
                                        const DetectorConfig& config) {
  std::vector<cv::KeyPoint> keypoints;
  cv::FAST(image, keypoints, threshold, true);
  std::vector<Candidate> candidates;
  double best = 0.0;
  for (const cv::KeyPoint& k : keypoints) {
    const int u = cvRound(k.pt.x), v = cvRound(k.pt.y);
    if (!free.at<std::uint8_t>(v, u)) continue;
    const double score = shiTomasiScore(image, u, v, config.score_window_px);
    best = std::max(best, score);
    candidates.push_back({cv::Point2f(static_cast<float>(u), static_cast<float>(v)), score});
  }
  const double floor = std::max(config.quality_level * best, 1e-9);
  candidates.erase(std::remove_if(candidates.begin(), candidates.end(),
                                  [&](const Candidate& c) { return c.score < floor; }),
                   candidates.end());
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
  return candidates;
}

}  // namespace

std::vector<cv::Point2f> detectCorners(const cv::Mat& image,
                                       const std::vector<cv::Point2f>& existing, int wanted,
                                       const DetectorConfig& config) {
  std::vector<cv::Point2f> chosen;
  const cv::Size size = image.size();
  if (wanted <= 0 || size.width <= 2 * config.border_px || size.height <= 2 * config.border_px) {
    return chosen;
  }
  cv::Mat free = freeMask(size, existing, config);
  const int cells = config.grid_cols * config.grid_rows;
  const int quota = std::max(1, (config.target_features + cells - 1) / cells);
  std::vector<int> per_cell(cells, 0);
  for (const cv::Point2f& p : existing) ++per_cell[cellOf(p, size, config)];
  const int radius = static_cast<int>(std::ceil(config.min_distance_px));
  // Strong corners first; where they cannot fill the budget (low-contrast walls), once more at
  // half the FAST threshold in the space left.
  for (int threshold : {config.fast_threshold, config.fast_threshold / 2}) {
    if (threshold < 1 || static_cast<int>(chosen.size()) >= wanted) break;
    const std::vector<Candidate> candidates = scoredCandidates(image, free, threshold, config);
    std::vector<bool> taken(candidates.size(), false);
    // Pass 1 respects the quota; pass 2 fills what is left with the strongest remaining
    // corners. Each accepted corner blocks its min_distance disc in the free mask.
    for (int pass = 0; pass < 2; ++pass) {
      for (std::size_t i = 0; i < candidates.size() && static_cast<int>(chosen.size()) < wanted;
           ++i) {
        const cv::Point2f& p = candidates[i].uv;
        if (taken[i] || !free.at<std::uint8_t>(cvRound(p.y), cvRound(p.x))) continue;
        int& count = per_cell[cellOf(p, size, config)];
        if (pass == 0 && count >= quota) continue;
        ++count;
        taken[i] = true;
        chosen.push_back(p);
        cv::circle(free, cv::Point(cvRound(p.x), cvRound(p.y)), radius, cv::Scalar(0), cv::FILLED);
      }
    }
  }
  return chosen;
}

}  // namespace strata::odometry
