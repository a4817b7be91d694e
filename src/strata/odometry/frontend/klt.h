#pragma once
// Pyramidal Lucas-Kanade tracking with a forward-backward check (Kalonia et al., "Forward-backward
// error", ICPR 2010): a point is kept only if tracking it back lands within fwd_bwd_max_px of
// where it started, which drops drifting points at occlusions and on repetitive texture.
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace strata::odometry {

struct KltConfig {
  int window_px = 15;           // LK window side; larger follows bigger motion, costs quadratically
  int pyramid_levels = 3;       // levels above the base; each doubles the capture range
  int max_iterations = 30;      // per level
  double epsilon_px = 0.01;     // LK stops when the update is below this
  double fwd_bwd_max_px = 0.5;  // forward-backward round trip error bound

  /// Throws InputError naming the bad field.
  void validate() const;
};

/// A pyramid with derivatives (cv::buildOpticalFlowPyramid), built once per image and shared by
/// every KLT call on that image.
std::vector<cv::Mat> buildPyramid(const cv::Mat& image, const KltConfig& config);

enum class KltStatus : std::uint8_t { kOk, kFailed, kFwdBwd };

/// Tracks `from` (in pyramid_from) into pyramid_to. `to` holds the initial guesses on input (same
/// size as `from`) and the results on output. A point fails (kFailed) when LK does not converge
/// or ends outside the image minus border_px; kFwdBwd when the backward track misses.
std::vector<KltStatus> trackForwardBackward(const std::vector<cv::Mat>& pyramid_from,
                                            const std::vector<cv::Mat>& pyramid_to,
                                            const std::vector<cv::Point2f>& from,
                                            std::vector<cv::Point2f>* to, cv::Size image_size,
                                            double border_px, const KltConfig& config);

}  // namespace strata::odometry
