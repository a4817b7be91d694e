#include "strata/odometry/frontend/appearance_check.h"

#include <opencv2/imgproc.hpp>

namespace strata::odometry {

cv::Mat normalizedPatch(const cv::Mat& image, cv::Point2f uv_px, int patch_px) {
  cv::Mat patch;
  cv::getRectSubPix(image, cv::Size(patch_px, patch_px), uv_px, patch, CV_32F);
  patch -= cv::mean(patch)[0];
  const double norm = cv::norm(patch);
  if (norm < 1e-3 * patch_px) return cv::Mat();
  return patch / norm;
}

double patchNcc(const cv::Mat& a, const cv::Mat& b) {
  if (a.empty() || b.empty()) return -1.0;
  return a.dot(b);
}

}  // namespace strata::odometry
