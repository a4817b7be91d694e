// The pictures of `strata explore` (explore_outputs.h): explored share vs simulated time, and
// the flown path over the final map's ESDF slice.
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "cli/bgr_image.h"
#include "cli/esdf_slice.h"
#include "cli/explore_outputs.h"
#include "strata/io/image_io.h"

namespace strata::apps {
namespace {

constexpr int kWidth = 960, kHeight = 540;
constexpr int kLeft = 80, kRight = 30, kTop = 50, kBottom = 60;
const cv::Scalar kColours[] = {{40, 110, 230}, {60, 160, 40}, {200, 80, 60}, {120, 60, 160}};

cv::Mat fromColorImage(const ColorImage& image) {
  cv::Mat out(image.height_px, image.width_px, CV_8UC3);
  for (int y = 0; y < image.height_px; ++y) {
    for (int x = 0; x < image.width_px; ++x) {
      const std::size_t i = 3 * (static_cast<std::size_t>(y) * image.width_px + x);
      out.at<cv::Vec3b>(y, x) = {image.rgb[i + 2], image.rgb[i + 1], image.rgb[i]};
    }
  }
  return out;
}

void text(cv::Mat& m, const std::string& s, int x, int y, double scale = 0.5) {
  cv::putText(m, s, {x, y}, cv::FONT_HERSHEY_SIMPLEX, scale, {30, 30, 30}, 1, cv::LINE_AA);
}

double niceStep(double range) {
  const double raw = range / 6.0;
  const double base = std::pow(10.0, std::floor(std::log10(raw)));
  for (double f : {1.0, 2.0, 5.0, 10.0}) {
    if (f * base >= raw) return f * base;
  }
  return 10.0 * base;
}

}  // namespace

void writeExploreCurvePng(const std::string& path, const std::string& world,
                          const std::vector<explore::ExplorationResult>& results) {
  cv::Mat m(kHeight, kWidth, CV_8UC3, cv::Scalar(255, 255, 255));
  double t_max = 1.0;
  for (const auto& r : results) {
    if (!r.curve.empty()) t_max = std::max(t_max, r.curve.back().sim_time_s);
  }
  const int w = kWidth - kLeft - kRight, h = kHeight - kTop - kBottom;
  auto px = [&](double t, double f) {
    return cv::Point(kLeft + static_cast<int>(std::lround(t / t_max * w)),
                     kTop + h - static_cast<int>(std::lround(f * h)));
  };
  const double step = niceStep(t_max);
  for (double t = 0.0; t <= t_max + 1e-9; t += step) {
    cv::line(m, px(t, 0.0), px(t, 1.0), {225, 225, 225}, 1);
    char label[32];
    std::snprintf(label, sizeof(label), "%g", t);
    text(m, label, px(t, 0.0).x - 10, kTop + h + 20);
  }
  for (int k = 0; k <= 10; ++k) {
    cv::line(m, px(0.0, k / 10.0), px(t_max, k / 10.0), {225, 225, 225}, 1);
    text(m, std::to_string(k * 10) + "%", 25, px(0.0, k / 10.0).y + 5);
  }
  cv::rectangle(m, px(0.0, 1.0), px(t_max, 0.0), {90, 90, 90}, 1);
  text(m, "explored share of the reachable free volume vs simulated time: " + world, kLeft, 30,
       0.6);
  text(m, "simulated time (s)", kLeft + w / 2 - 70, kHeight - 15);
  for (std::size_t i = 0; i < results.size(); ++i) {
    const auto& curve = results[i].curve;
    const cv::Scalar colour = kColours[i % 4];
    for (std::size_t k = 1; k < curve.size(); ++k) {
      cv::line(m, px(curve[k - 1].sim_time_s, curve[k - 1].explored_fraction),
               px(curve[k].sim_time_s, curve[k].explored_fraction), colour, 2, cv::LINE_AA);
    }
    const int y = kTop + h - 30 - 22 * static_cast<int>(i);
    cv::line(m, {kLeft + w - 200, y - 5}, {kLeft + w - 170, y - 5}, colour, 3);
    text(m, results[i].planner, kLeft + w - 160, y);
  }
  writeColorPng(path, colorImageFromBgr(m));
}

void writeExplorePathPng(const std::string& path, const EsdfMap& esdf,
                         const explore::ExplorationResult& result, float z_m) {
  EsdfSliceOptions options;
  options.z_m = z_m;
  char title[160];
  std::snprintf(title, sizeof(title), "%s: FLOWN PATH (RED) OVER THE ESDF AT Z=%.2f M, %.0f S",
                result.planner.c_str(), static_cast<double>(z_m), result.sim_time_s);
  options.title = title;
  std::string upper = options.title;
  std::transform(upper.begin(), upper.end(), upper.begin(), ::toupper);
  options.title = upper;
  const EsdfSlice slice = renderEsdfSlice(esdf, options);
  cv::Mat m = fromColorImage(slice.image);
  auto pixel = [&](const Eigen::Vector3f& p) {
    const Eigen::Vector2f q = slicePixel(slice.stats, esdf.voxel_size_m, p.x(), p.y());
    return cv::Point(static_cast<int>(std::lround(q.x())), static_cast<int>(std::lround(q.y())));
  };
  for (std::size_t i = 1; i < result.flown_W.size(); ++i) {
    cv::line(m, pixel(result.flown_W[i - 1]), pixel(result.flown_W[i]), {30, 30, 220}, 2,
             cv::LINE_AA);
  }
  if (!result.flown_W.empty()) {
    cv::circle(m, pixel(result.flown_W.front()), 6, {30, 200, 30}, -1, cv::LINE_AA);
    cv::circle(m, pixel(result.flown_W.back()), 6, {30, 30, 30}, 2, cv::LINE_AA);
  }
  writeColorPng(path, colorImageFromBgr(m));
}

}  // namespace strata::apps
