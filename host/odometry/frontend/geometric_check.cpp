#include "odometry/frontend/geometric_check.h"

#include <opencv2/calib3d.hpp>

#include <algorithm>

#include "core/error.h"

namespace strata::odometry {
namespace {

std::vector<cv::Point2f> toCv(const std::vector<Eigen::Vector2d>& points) {
  std::vector<cv::Point2f> out;
  out.reserve(points.size());
  for (const Eigen::Vector2d& p : points) {
    out.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
  }
  return out;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

void GeometricCheckConfig::validate() const {
  if (!(ransac_threshold_px > 0.0)) {
    throw InputError("GeometricCheckConfig: ransac_threshold_px must be > 0");
  }
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw InputError("GeometricCheckConfig: confidence must be in (0, 1)");
  }
  if (!(homography_below_parallax_px >= 0.0)) {
    throw InputError("GeometricCheckConfig: homography_below_parallax_px must be >= 0");
  }
  if (min_correspondences < 8) {
    throw InputError("GeometricCheckConfig: min_correspondences must be >= 8");
  }
}

double rotationCompensatedParallaxPx(const Eigen::Vector2d& xy_prev, const Eigen::Vector2d& xy_cur,
                                     const std::optional<Eigen::Matrix3d>& R_cur_prev,
                                     double focal_px) {
  Eigen::Vector2d predicted = xy_prev;
  if (R_cur_prev) {
    const Eigen::Vector3d bearing = *R_cur_prev * xy_prev.homogeneous();
    // Behind the camera after rotation: no meaningful prediction, use the raw displacement.
    if (bearing.z() > 1e-6) predicted = bearing.hnormalized();
  }
  return (xy_cur - predicted).norm() * focal_px;
}

GeometricCheckResult rejectOutliers(const std::vector<Eigen::Vector2d>& xy_prev,
                                    const std::vector<Eigen::Vector2d>& xy_cur,
                                    const std::optional<Eigen::Matrix3d>& R_cur_prev,
                                    double focal_px, const GeometricCheckConfig& config) {
  if (xy_prev.size() != xy_cur.size()) {
    throw Error("rejectOutliers: previous and current point lists differ in size");
  }
  GeometricCheckResult result;
  result.inlier.assign(xy_cur.size(), 1);
  std::vector<double> parallax(xy_cur.size());
  for (std::size_t i = 0; i < xy_cur.size(); ++i) {
    parallax[i] = rotationCompensatedParallaxPx(xy_prev[i], xy_cur[i], R_cur_prev, focal_px);
  }
  result.median_parallax_px = median(parallax);
  if (static_cast<int>(xy_cur.size()) < config.min_correspondences) return result;

  const std::vector<cv::Point2f> prev = toCv(xy_prev), cur = toCv(xy_cur);
  const double threshold = config.ransac_threshold_px / focal_px;
  std::vector<unsigned char> mask;
  cv::Mat model;
  if (result.median_parallax_px < config.homography_below_parallax_px) {
    result.model = 'H';
    model = cv::findHomography(prev, cur, cv::RANSAC, threshold, mask, 2000, config.confidence);
  } else {
    result.model = 'E';
    model = cv::findEssentialMat(prev, cur, 1.0, cv::Point2d(0, 0), cv::RANSAC, config.confidence,
                                 threshold, mask);
  }
  // No model found (degenerate sample sets): keep everything rather than drop a whole frame.
  if (model.empty() || mask.size() != xy_cur.size()) {
    result.model = '-';
    return result;
  }
  result.inlier = mask;
  result.rejected =
      static_cast<int>(std::count(mask.begin(), mask.end(), static_cast<unsigned char>(0)));
  return result;
}

}  // namespace strata::odometry
