#include "strata/odometry/frontend/geometric_check.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>

#include "strata/core/error.h"

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

// Squared error of one correspondence under H (transfer) or F (Sampson), normalized units.
double squaredError(const cv::Mat& model, char kind, const Eigen::Vector2d& a,
                    const Eigen::Vector2d& b) {
  Eigen::Matrix3d M;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) M(r, c) = model.at<double>(r, c);
  }
  if (kind == 'H') {
    const Eigen::Vector3d p = M * a.homogeneous();
    if (std::abs(p.z()) < 1e-12) return 1e30;
    return (p.hnormalized() - b).squaredNorm();
  }
  const Eigen::Vector3d Fa = M * a.homogeneous(), Ftb = M.transpose() * b.homogeneous();
  const double e = b.homogeneous().dot(Fa);
  const double denominator = Fa.head<2>().squaredNorm() + Ftb.head<2>().squaredNorm();
  return denominator > 0.0 ? e * e / denominator : 1e30;
}

// RANSAC's mask comes from one minimal sample, whose noise drops good points near the bound.
// Local optimisation: refit by least squares on the inliers (homography DLT, or the 8-point
// fundamental matrix, which in normalized coordinates is an essential matrix up to its
// constraints), then take the inliers of the refit. Two rounds settle it.
void refitInliers(const std::vector<cv::Point2f>& a, const std::vector<cv::Point2f>& b,
                  const std::vector<Eigen::Vector2d>& xa, const std::vector<Eigen::Vector2d>& xb,
                  char kind, double threshold, std::vector<unsigned char>* mask) {
  for (int round = 0; round < 2; ++round) {
    std::vector<cv::Point2f> in_a, in_b;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if ((*mask)[i]) {
        in_a.push_back(a[i]);
        in_b.push_back(b[i]);
      }
    }
    if (in_a.size() < 12) return;
    const cv::Mat model = kind == 'H' ? cv::findHomography(in_a, in_b, 0)
                                      : cv::findFundamentalMat(in_a, in_b, cv::FM_8POINT);
    // An 8-point fit can come back 3k x 3 or empty on degenerate sets: keep the last mask.
    if (model.rows != 3 || model.cols != 3) return;
    for (std::size_t i = 0; i < a.size(); ++i) {
      (*mask)[i] = squaredError(model, kind, xa[i], xb[i]) <= threshold * threshold;
    }
  }
}

}  // namespace

void GeometricCheckConfig::validate() const {
  if (!(ransac_threshold_px > 0.0)) {
    throw InputError("GeometricCheckConfig: ransac_threshold_px must be > 0");
  }
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw InputError("GeometricCheckConfig: confidence must be in (0, 1)");
  }
  if (!(max_homography_reject_share >= 0.0 && max_homography_reject_share <= 1.0)) {
    throw InputError("GeometricCheckConfig: max_homography_reject_share must be in [0, 1]");
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
    if (!model.empty() && mask.size() == xy_cur.size()) {
      refitInliers(prev, cur, xy_prev, xy_cur, 'H', threshold, &mask);
    }
    // Small flow may still hide translation (rotation cancelling it, no prediction given):
    // then H drops good points of other depths, and E takes over.
    const auto rejected = std::count(mask.begin(), mask.end(), static_cast<unsigned char>(0));
    if (model.empty() || mask.size() != xy_cur.size() ||
        rejected > config.max_homography_reject_share * static_cast<double>(xy_cur.size())) {
      model = cv::Mat();
    }
  }
  if (model.empty()) {
    result.model = 'E';
    model = cv::findEssentialMat(prev, cur, 1.0, cv::Point2d(0, 0), cv::RANSAC, config.confidence,
                                 threshold, mask);
    if (!model.empty() && mask.size() == xy_cur.size()) {
      refitInliers(prev, cur, xy_prev, xy_cur, 'E', threshold, &mask);
    }
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
