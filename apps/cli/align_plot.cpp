#include "cli/align_plot.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "strata/io/image_io.h"

namespace strata::apps {
namespace {

constexpr int kPanel_px = 640;
constexpr int kAlignMargin_px = 30;
constexpr int kAlignCaption_px = 60;

const cv::Scalar kSessionColours[] = {{200, 110, 30}, {40, 140, 240}, {60, 170, 60},
                                      {180, 60, 180}, {30, 60, 200},  {160, 160, 30},
                                      {120, 80, 40},  {90, 90, 90}};

cv::Scalar sessionColour(std::size_t s) { return kSessionColours[s % std::size(kSessionColours)]; }

/// Maps world x (right) and y (up) into a square panel, both axes at one scale.
struct Panel {
  int x0 = 0;
  Eigen::Vector2d min_m{0, 0};
  double px_per_m = 1.0;
  cv::Point toPixel(const Eigen::Vector3d& p) const {
    const double u = x0 + kAlignMargin_px + (p.x() - min_m.x()) * px_per_m;
    const double v = kAlignMargin_px + kPanel_px - 2 * kAlignMargin_px - (p.y() - min_m.y()) * px_per_m;
    return {static_cast<int>(std::lround(u)), static_cast<int>(std::lround(v))};
  }
};

Panel fitPanel(int x0, const std::vector<const std::vector<Eigen::Isometry3d>*>& paths) {
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const auto* path : paths)
    for (const Eigen::Isometry3d& T : *path) {
      lo = lo.cwiseMin(T.translation().head<2>());
      hi = hi.cwiseMax(T.translation().head<2>());
    }
  Panel panel;
  panel.x0 = x0;
  if (lo.x() > hi.x()) return panel;
  const double extent = std::max((hi - lo).maxCoeff(), 1e-3);
  panel.px_per_m = (kPanel_px - 2 * kAlignMargin_px) / extent;
  panel.min_m = lo - 0.5 * (Eigen::Vector2d::Constant(extent) - (hi - lo));
  return panel;
}

void drawPath(cv::Mat& image, const Panel& panel, const std::vector<Eigen::Isometry3d>& path,
              const cv::Scalar& colour) {
  for (std::size_t i = 1; i < path.size(); ++i)
    cv::line(image, panel.toPixel(path[i - 1].translation()), panel.toPixel(path[i].translation()),
             colour, 1, cv::LINE_AA);
  if (!path.empty()) cv::circle(image, panel.toPixel(path.front().translation()), 4, colour, 2);
}

void drawScaleBar(cv::Mat& image, const Panel& panel) {
  const double target_m = 120.0 / panel.px_per_m;
  const double base_m = std::pow(10.0, std::floor(std::log10(target_m)));
  double bar_m = base_m;  // 1-2-5 steps
  for (double f : {2.0, 5.0})
    if (base_m * f <= target_m) bar_m = base_m * f;
  const int y = kPanel_px - 12, x = panel.x0 + kAlignMargin_px;
  const int len = static_cast<int>(std::lround(bar_m * panel.px_per_m));
  cv::line(image, {x, y}, {x + len, y}, {0, 0, 0}, 2);
  char text[32];
  std::snprintf(text, sizeof(text), "%g m", bar_m);
  cv::putText(image, text, {x + len + 6, y + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.45, {0, 0, 0}, 1,
              cv::LINE_AA);
}

}  // namespace

void writeAlignPlot(const std::string& png_path, const align::AlignResult& result,
                    const std::vector<std::string>& names) {
  cv::Mat image(kPanel_px + kAlignCaption_px, 2 * kPanel_px, CV_8UC3, cv::Scalar(255, 255, 255));
  std::vector<const std::vector<Eigen::Isometry3d>*> before, after;
  for (const align::AlignedSession& s : result.sessions) {
    before.push_back(&s.frame_T_S_C);
    if (s.aligned) after.push_back(&s.frame_T_W_C);
  }
  const Panel left = fitPanel(0, before), right = fitPanel(kPanel_px, after);
  for (std::size_t s = 0; s < result.sessions.size(); ++s) {
    drawPath(image, left, result.sessions[s].frame_T_S_C, sessionColour(s));
    if (result.sessions[s].aligned)
      drawPath(image, right, result.sessions[s].frame_T_W_C, sessionColour(s));
  }
  for (const align::AlignLoop& loop : result.loops) {
    const align::AlignedSession& a = result.sessions[loop.session_a];
    const align::AlignedSession& b = result.sessions[loop.session_b];
    if (!a.aligned || !b.aligned) continue;
    cv::line(image, right.toPixel(a.keyframe_T_W_C[loop.keyframe_a].translation()),
             right.toPixel(b.keyframe_T_W_C[loop.keyframe_b].translation()),
             loop.accepted ? cv::Scalar(60, 180, 60) : cv::Scalar(40, 40, 220), 1, cv::LINE_AA);
  }
  cv::line(image, {kPanel_px, 0}, {kPanel_px, kPanel_px}, {200, 200, 200}, 1);
  cv::putText(image, "odometry as given (each session in its own frame)", {12, 20},
              cv::FONT_HERSHEY_SIMPLEX, 0.5, {60, 60, 60}, 1, cv::LINE_AA);
  cv::putText(image, "aligned (common frame); loops: green kept, red switched off",
              {kPanel_px + 12, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.5, {60, 60, 60}, 1, cv::LINE_AA);
  if (!before.empty()) drawScaleBar(image, left);
  if (!after.empty()) drawScaleBar(image, right);
  int x = 12;
  for (std::size_t s = 0; s < names.size(); ++s) {
    const std::string label =
        names[s] + (result.sessions[s].aligned ? "" : " (unaligned)");
    cv::putText(image, label, {x, kPanel_px + 36}, cv::FONT_HERSHEY_SIMPLEX, 0.5,
                sessionColour(s), 1, cv::LINE_AA);
    x += 14 + 9 * static_cast<int>(label.size());
  }
  ColorImage rgb(image.cols, image.rows);
  for (int y = 0; y < image.rows; ++y)
    for (int c = 0; c < image.cols; ++c) {
      const cv::Vec3b bgr = image.at<cv::Vec3b>(y, c);
      std::uint8_t* out = &rgb.rgb[3 * (static_cast<std::size_t>(y) * image.cols + c)];
      out[0] = bgr[2], out[1] = bgr[1], out[2] = bgr[0];
    }
  writeColorPng(png_path, rgb);
}

}  // namespace strata::apps
