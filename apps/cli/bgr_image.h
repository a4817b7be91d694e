#pragma once
// An OpenCV BGR image (CV_8UC3, as the plots draw them) as the project's RGB ColorImage.
#include <opencv2/core.hpp>

#include "strata/core/types.h"

namespace strata::apps {

inline ColorImage colorImageFromBgr(const cv::Mat& bgr) {
  ColorImage out(bgr.cols, bgr.rows);
  for (int y = 0; y < bgr.rows; ++y) {
    for (int x = 0; x < bgr.cols; ++x) {
      const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
      const std::size_t i = 3 * (static_cast<std::size_t>(y) * bgr.cols + x);
      out.rgb[i] = p[2];
      out.rgb[i + 1] = p[1];
      out.rgb[i + 2] = p[0];
    }
  }
  return out;
}

}  // namespace strata::apps
