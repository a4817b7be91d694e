#include "strata/odometry/frontend/klt.h"

#include <opencv2/video/tracking.hpp>

#include "strata/core/error.h"

namespace strata::odometry {
namespace {

bool inside(const cv::Point2f& p, cv::Size size, double border_px) {
  return p.x >= border_px && p.y >= border_px && p.x <= size.width - 1 - border_px &&
         p.y <= size.height - 1 - border_px;
}

cv::TermCriteria criteria(const KltConfig& config) {
  return {cv::TermCriteria::COUNT | cv::TermCriteria::EPS, config.max_iterations,
          config.epsilon_px};
}

}  // namespace

void KltConfig::validate() const {
  if (window_px < 5 || window_px % 2 == 0)
    throw InputError("KltConfig: window_px must be odd, >= 5");
  if (pyramid_levels < 0 || pyramid_levels > 6) {
    throw InputError("KltConfig: pyramid_levels must be in [0, 6]");
  }
  if (max_iterations < 1) throw InputError("KltConfig: max_iterations must be >= 1");
  if (!(epsilon_px > 0.0)) throw InputError("KltConfig: epsilon_px must be > 0");
  if (!(fwd_bwd_max_px > 0.0)) throw InputError("KltConfig: fwd_bwd_max_px must be > 0");
}

std::vector<cv::Mat> buildPyramid(const cv::Mat& image, const KltConfig& config) {
  std::vector<cv::Mat> pyramid;
  cv::buildOpticalFlowPyramid(image, pyramid, cv::Size(config.window_px, config.window_px),
                              config.pyramid_levels, true);
  return pyramid;
}

std::vector<KltStatus> trackForwardBackward(const std::vector<cv::Mat>& pyramid_from,
                                            const std::vector<cv::Mat>& pyramid_to,
                                            const std::vector<cv::Point2f>& from,
                                            std::vector<cv::Point2f>* to, cv::Size image_size,
                                            double border_px, const KltConfig& config) {
  std::vector<KltStatus> result(from.size(), KltStatus::kFailed);
  if (from.empty()) return result;
  const cv::Size window(config.window_px, config.window_px);
  std::vector<unsigned char> status;
  std::vector<float> error;
  cv::calcOpticalFlowPyrLK(pyramid_from, pyramid_to, from, *to, status, error, window,
                           config.pyramid_levels, criteria(config), cv::OPTFLOW_USE_INITIAL_FLOW);
  // Backward pass only for the points that made it forward, starting from where they started.
  std::vector<int> index;
  std::vector<cv::Point2f> back_from, back_to;
  for (std::size_t i = 0; i < from.size(); ++i) {
    if (!status[i] || !inside((*to)[i], image_size, border_px)) continue;
    index.push_back(static_cast<int>(i));
    back_from.push_back((*to)[i]);
    back_to.push_back(from[i]);
  }
  if (index.empty()) return result;
  cv::calcOpticalFlowPyrLK(pyramid_to, pyramid_from, back_from, back_to, status, error, window,
                           config.pyramid_levels, criteria(config), cv::OPTFLOW_USE_INITIAL_FLOW);
  const double max_sq = config.fwd_bwd_max_px * config.fwd_bwd_max_px;
  for (std::size_t j = 0; j < index.size(); ++j) {
    const cv::Point2f d = back_to[j] - from[index[j]];
    const bool returned = status[j] && d.x * d.x + d.y * d.y <= max_sq;
    result[index[j]] = returned ? KltStatus::kOk : KltStatus::kFwdBwd;
  }
  return result;
}

}  // namespace strata::odometry
