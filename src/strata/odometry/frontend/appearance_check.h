#pragma once
// Appearance check of a track against the patch it was detected with (Shi and Tomasi, "Good
// features to track", CVPR 1994: monitor the dissimilarity to the first frame). KLT and the
// epipolar check both miss corners that are not points of the world, above all T-junctions
// where a foreground edge crosses a background edge: their image position slides along the
// edge as the view changes, often along the epipolar line, a fraction of a pixel per frame. Their
// patch, half foreground and half background, changes meanwhile; a true point's patch does not.
#include <opencv2/core.hpp>

namespace strata::odometry {

/// The patch_px x patch_px patch around subpixel `uv_px` (bilinear), zero-mean and unit-norm,
/// CV_32F; empty when the patch is flat (no texture to compare).
cv::Mat normalizedPatch(const cv::Mat& image, cv::Point2f uv_px, int patch_px);

/// Zero-mean normalized cross-correlation of two normalizedPatch results in [-1, 1]; -1 when
/// either is empty.
double patchNcc(const cv::Mat& a, const cv::Mat& b);

}  // namespace strata::odometry
