#include "cli/trajectory_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "strata/core/error.h"
#include "strata/io/image_io.h"

namespace strata::apps {
namespace {

constexpr int kWidth_px = 960;
constexpr int kMargin_px = 40;
constexpr int kCaption_px = 48;

struct View {
  int axis_u = 0, axis_v = 1;  // world axes drawn right and up
  Eigen::Vector3d min_m, max_m;
  double px_per_m = 1.0;
  int height_px = 0;
  cv::Point toPixel(const Eigen::Vector3d& p) const {
    const double u = kMargin_px + (p[axis_u] - min_m[axis_u]) * px_per_m;
    const double v = height_px - kCaption_px - kMargin_px - (p[axis_v] - min_m[axis_v]) * px_per_m;
    return {static_cast<int>(std::lround(u)), static_cast<int>(std::lround(v))};
  }
};

View makeView(const trajectory::TrajectoryError& e) {
  View view;
  view.min_m = view.max_m = e.truth_positions_m.front();
  for (const auto* set : {&e.truth_positions_m, &e.estimate_positions_m}) {
    for (const Eigen::Vector3d& p : *set) {
      view.min_m = view.min_m.cwiseMin(p);
      view.max_m = view.max_m.cwiseMax(p);
    }
  }
  const Eigen::Vector3d extent = (view.max_m - view.min_m).cwiseMax(1e-3);
  // Drop the axis of least extent; the other two keep their order (x right of y, etc.).
  int drop = 0;
  extent.minCoeff(&drop);
  view.axis_u = drop == 0 ? 1 : 0;
  view.axis_v = drop == 2 ? 1 : 2;
  const double plot_w = kWidth_px - 2 * kMargin_px;
  view.px_per_m = plot_w / extent[view.axis_u];
  const double max_plot_h = 720.0;
  if (extent[view.axis_v] * view.px_per_m > max_plot_h) view.px_per_m = max_plot_h / extent[view.axis_v];
  view.height_px = static_cast<int>(extent[view.axis_v] * view.px_per_m) + 2 * kMargin_px + kCaption_px;
  return view;
}

/// The largest 1, 2 or 5 times a power of ten not longer than a quarter of the plot width.
double scaleBarLength_m(double px_per_m) {
  const double max_m = 0.25 * (kWidth_px - 2 * kMargin_px) / px_per_m;
  const double decade = std::pow(10.0, std::floor(std::log10(max_m)));
  for (double f : {5.0, 2.0, 1.0}) {
    if (f * decade <= max_m) return f * decade;
  }
  return decade;
}

void drawPath(cv::Mat& image, const View& view, const std::vector<Eigen::Vector3d>& path,
              const cv::Scalar& bgr, int thickness) {
  for (std::size_t i = 1; i < path.size(); ++i) {
    cv::line(image, view.toPixel(path[i - 1]), view.toPixel(path[i]), bgr, thickness, cv::LINE_AA);
  }
}

void drawCaption(cv::Mat& image, const View& view, const trajectory::TrajectoryError& e) {
  const char* axes = "xyz";
  char text[256];
  std::snprintf(text, sizeof text,
                "ATE RMSE %.3f m (%.2f %% of %.2f m), alignment %s, %zu poses; view %c right, %c up",
                e.ate_rmse_m, e.path_length_m > 0 ? 100.0 * e.ate_rmse_m / e.path_length_m : 0.0,
                e.path_length_m, trajectory::alignmentName(e.alignment), e.matched, axes[view.axis_u],
                axes[view.axis_v]);
  const int y = view.height_px - kCaption_px / 2;
  cv::putText(image, text, {kMargin_px, y}, cv::FONT_HERSHEY_SIMPLEX, 0.45, {40, 40, 40}, 1, cv::LINE_AA);
  cv::putText(image, "truth", {kMargin_px, 24}, cv::FONT_HERSHEY_SIMPLEX, 0.5, {120, 120, 120}, 1, cv::LINE_AA);
  cv::putText(image, "estimate", {kMargin_px + 70, 24}, cv::FONT_HERSHEY_SIMPLEX, 0.5, {0, 120, 240}, 1,
              cv::LINE_AA);
  const double bar_m = scaleBarLength_m(view.px_per_m);
  const int bar_px = static_cast<int>(std::lround(bar_m * view.px_per_m));
  const int x1 = kWidth_px - kMargin_px, x0 = x1 - bar_px, yb = 20;
  cv::line(image, {x0, yb}, {x1, yb}, {0, 0, 0}, 2);
  std::snprintf(text, sizeof text, "%g m", bar_m);
  cv::putText(image, text, {x0 - 60, yb + 5}, cv::FONT_HERSHEY_SIMPLEX, 0.45, {0, 0, 0}, 1, cv::LINE_AA);
}

}  // namespace

void writeTrajectoryPlot(const std::string& png_path, const trajectory::TrajectoryError& e) {
  if (e.truth_positions_m.empty()) throw InputError("trajectory plot: no matched poses to draw");
  const View view = makeView(e);
  cv::Mat image(view.height_px, kWidth_px, CV_8UC3, cv::Scalar(255, 255, 255));
  // Error segments every few poses so a long trajectory stays readable.
  const std::size_t step = std::max<std::size_t>(1, e.truth_positions_m.size() / 100);
  for (std::size_t i = 0; i < e.truth_positions_m.size(); i += step) {
    cv::line(image, view.toPixel(e.truth_positions_m[i]), view.toPixel(e.estimate_positions_m[i]),
             {180, 180, 255}, 1, cv::LINE_AA);
  }
  drawPath(image, view, e.truth_positions_m, {120, 120, 120}, 2);
  drawPath(image, view, e.estimate_positions_m, {0, 120, 240}, 1);
  cv::circle(image, view.toPixel(e.truth_positions_m.front()), 5, {0, 160, 0}, 2, cv::LINE_AA);
  drawCaption(image, view, e);
  ColorImage rgb(image.cols, image.rows);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      const cv::Vec3b bgr = image.at<cv::Vec3b>(y, x);
      std::uint8_t* out = &rgb.rgb[3 * (static_cast<std::size_t>(y) * image.cols + x)];
      out[0] = bgr[2];
      out[1] = bgr[1];
      out[2] = bgr[0];
    }
  }
  writeColorPng(png_path, rgb);
}

}  // namespace strata::apps
