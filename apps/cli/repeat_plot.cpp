#include "cli/repeat_plot.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "cli/bgr_image.h"
#include "strata/io/image_io.h"

namespace strata::apps {
namespace {

constexpr int kTopDownWidthPx = 960;
constexpr int kTopDownMarginPx = 40, kTopDownLegendPx = 28, kTopDownLinePx = 20;

struct TopDownView {
  Eigen::Vector2d min;
  double scale;  // px per metre
  int top;       // px of the map's top edge
  int height;    // px of the map area
  cv::Point px(const Eigen::Vector2d& p) const {
    return {kTopDownMarginPx + static_cast<int>(std::lround((p.x() - min.x()) * scale)),
            top + height - static_cast<int>(std::lround((p.y() - min.y()) * scale))};
  }
};

cv::Scalar topDownBgr(const std::array<int, 3>& rgb) {
  return {double(rgb[2]), double(rgb[1]), double(rgb[0])};
}

void topDownText(cv::Mat& m, const std::string& s, cv::Point at, double scale = 0.5) {
  cv::putText(m, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, {30, 30, 30}, 1, cv::LINE_AA);
}

double topDownScaleBarM(double metres_across) {
  const double raw = metres_across / 5.0;
  const double base = std::pow(10.0, std::floor(std::log10(raw)));
  for (double f : {1.0, 2.0, 5.0}) {
    if (f * base >= raw) return f * base;
  }
  return 10.0 * base;
}

}  // namespace

void writeTopDownPng(const std::string& png_path, const sim::World& world,
                     const std::vector<PlotSeries>& series,
                     const std::vector<std::string>& caption) {
  const Eigen::AlignedBox3d b = world.bounds();
  const Eigen::Vector2d lo = b.min().head<2>(), size = b.sizes().head<2>().cwiseMax(0.1);
  TopDownView view;
  view.min = lo;
  view.scale = (kTopDownWidthPx - 2 * kTopDownMarginPx) / size.x();
  view.height = static_cast<int>(std::ceil(size.y() * view.scale));
  view.top = kTopDownMarginPx + kTopDownLegendPx;
  const int height =
      view.top + view.height + kTopDownMarginPx + kTopDownLinePx * static_cast<int>(caption.size());
  cv::Mat m(height, kTopDownWidthPx, CV_8UC3, cv::Scalar(255, 255, 255));
  for (const sim::RoomSpec& room : world.spec().rooms) {
    cv::rectangle(m, view.px(room.min_m), view.px(room.max_m), {200, 200, 200}, 2);
  }
  int legend_x = kTopDownMarginPx;
  for (const PlotSeries& s : series) {
    std::vector<cv::Point> line;
    for (const Eigen::Vector3f& p : s.points) line.push_back(view.px(p.head<2>().cast<double>()));
    if (line.size() >= 2) {
      cv::polylines(m, line, false, topDownBgr(s.rgb), s.thickness_px, cv::LINE_AA);
    }
    if (!line.empty()) cv::circle(m, line.front(), 5, topDownBgr(s.rgb), cv::FILLED, cv::LINE_AA);
    cv::line(m, {legend_x, kTopDownMarginPx}, {legend_x + 30, kTopDownMarginPx}, topDownBgr(s.rgb),
             3, cv::LINE_AA);
    topDownText(m, s.label, {legend_x + 36, kTopDownMarginPx + 5});
    legend_x += 50 + 9 * static_cast<int>(s.label.size());
  }
  const double bar_m = topDownScaleBarM(size.x());
  const int bar_px = static_cast<int>(std::lround(bar_m * view.scale));
  const int bar_y = view.top + view.height + 20;
  cv::line(m, {kTopDownMarginPx, bar_y}, {kTopDownMarginPx + bar_px, bar_y}, {30, 30, 30}, 2);
  char label[32];
  std::snprintf(label, sizeof(label), "%g m", bar_m);
  topDownText(m, label, {kTopDownMarginPx + bar_px + 8, bar_y + 5});
  for (std::size_t i = 0; i < caption.size(); ++i) {
    topDownText(m, caption[i],
                {kTopDownMarginPx, bar_y + 22 + kTopDownLinePx * static_cast<int>(i)});
  }
  writeColorPng(png_path, colorImageFromBgr(m));
}

}  // namespace strata::apps
