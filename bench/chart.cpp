#include "chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "strata/core/atomic_file.h"
#include "strata/core/error.h"

namespace strata::bench {
namespace {

constexpr int kWidthPx = 960;
constexpr int kHeightPx = 540;
// Plot area inside the image: room for the title, the axis labels and the legend on the right.
constexpr int kLeftPx = 80;
constexpr int kRightPx = 720;
constexpr int kTopPx = 60;
constexpr int kBottomPx = 470;
const cv::Scalar kInk(40, 40, 40);
const cv::Scalar kGrid(225, 225, 225);
constexpr ChartColor kMarkColor = {190, 190, 190};  // event lines: visible, behind the data
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

cv::Scalar bgr(const ChartColor& c) { return cv::Scalar(c[2], c[1], c[0]); }

void text(cv::Mat& image, const std::string& s, cv::Point at, double scale = 0.45,
          const cv::Scalar& color = kInk, bool centred = false) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(s, kFont, scale, 1, &baseline);
  if (centred) at.x -= size.width / 2;
  cv::putText(image, s, at, kFont, scale, color, 1, cv::LINE_AA);
}

/// 1, 2 or 5 times a power of ten, about range / 5.
double niceStep(double range) {
  if (!(range > 0.0)) return 1.0;
  const double raw = range / 5.0;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  const double m = raw / power;
  return (m <= 1.0 ? 1.0 : m <= 2.0 ? 2.0 : m <= 5.0 ? 5.0 : 10.0) * power;
}

struct Axis {
  double min = 0.0;
  double max = 1.0;
  double step = 0.2;
};

Axis niceAxis(double lo, double hi) {
  if (!(hi > lo)) hi = lo + 1.0;
  Axis a;
  a.step = niceStep(hi - lo);
  a.min = std::floor(lo / a.step) * a.step;
  a.max = std::ceil(hi / a.step) * a.step;
  if (a.max <= a.min) a.max = a.min + a.step;
  return a;
}

int yPx(const Axis& a, double v) {
  return kBottomPx - static_cast<int>(std::lround((v - a.min) / (a.max - a.min) *
                                                  (kBottomPx - kTopPx)));
}

int xPx(const Axis& a, double v) {
  return kLeftPx + static_cast<int>(std::lround((v - a.min) / (a.max - a.min) *
                                                (kRightPx - kLeftPx)));
}

cv::Mat canvas(const std::string& title) {
  cv::Mat image(kHeightPx, kWidthPx, CV_8UC3, cv::Scalar(255, 255, 255));
  text(image, title, {kLeftPx, 22}, 0.6);
  return image;
}

void yAxis(cv::Mat& image, const Axis& a, const std::string& label) {
  for (double v = a.min; v <= a.max + 0.5 * a.step; v += a.step) {
    const int y = yPx(a, v);
    cv::line(image, {kLeftPx, y}, {kRightPx, y}, kGrid, 1);
    text(image, formatTick(v), {kLeftPx - 45, y + 4}, 0.4);
  }
  cv::line(image, {kLeftPx, kTopPx}, {kLeftPx, kBottomPx}, kInk, 1);
  cv::line(image, {kLeftPx, kBottomPx}, {kRightPx, kBottomPx}, kInk, 1);
  text(image, label, {8, kTopPx - 10}, 0.45);
}

void legend(cv::Mat& image, const std::vector<std::pair<std::string, ChartColor>>& entries) {
  int y = kTopPx + 10;
  for (const auto& [name, color] : entries) {
    cv::rectangle(image, {kRightPx + 20, y - 10}, {kRightPx + 34, y + 2}, bgr(color), cv::FILLED);
    text(image, name, {kRightPx + 42, y}, 0.42);
    y += 22;
  }
}

void dashedLine(cv::Mat& image, int y, const cv::Scalar& color) {
  for (int x = kLeftPx; x < kRightPx; x += 12) {
    cv::line(image, {x, y}, {std::min(x + 7, kRightPx), y}, color, 2, cv::LINE_AA);
  }
}

double barTop(const ChartBar& bar) {
  double sum = 0.0;
  for (const double s : bar.segments) sum += std::max(0.0, s);
  return sum;
}

}  // namespace

std::string formatTick(double value) {
  char buffer[32];
  if (std::abs(value) >= 1000.0) {
    std::snprintf(buffer, sizeof(buffer), "%.0f", value);
  } else {
    std::snprintf(buffer, sizeof(buffer), "%.3g", std::abs(value) < 1e-12 ? 0.0 : value);
  }
  return buffer;
}

cv::Mat drawBarChart(const BarChart& chart) {
  cv::Mat image = canvas(chart.title);
  double top = std::max(0.0, chart.reference_value);
  std::size_t bar_count = 0;
  for (const ChartGroup& g : chart.groups) {
    for (const ChartBar& b : g.bars) top = std::max(top, barTop(b));
    bar_count += g.bars.size();
  }
  const Axis axis = niceAxis(0.0, top * 1.08);
  yAxis(image, axis, chart.y_label);
  std::vector<std::pair<std::string, ChartColor>> entries;
  for (const ChartSeries& s : chart.series) entries.emplace_back(s.name, s.color);
  legend(image, entries);
  if (bar_count == 0) {
    text(image, "no data", {(kLeftPx + kRightPx) / 2, (kTopPx + kBottomPx) / 2}, 0.7, kInk, true);
    return image;
  }
  // Slots: one per bar plus one gap per group boundary.
  const double slots = static_cast<double>(bar_count + chart.groups.size());
  const double slot_px = (kRightPx - kLeftPx) / slots;
  double x = kLeftPx + 0.5 * slot_px;
  for (const ChartGroup& g : chart.groups) {
    const double group_start = x;
    for (const ChartBar& b : g.bars) {
      const int x0 = static_cast<int>(x + 0.1 * slot_px);
      const int x1 = static_cast<int>(x + 0.9 * slot_px);
      double base = 0.0;
      for (std::size_t i = 0; i < b.segments.size(); ++i) {
        const double v = std::max(0.0, b.segments[i]);
        const std::size_t si = i < b.segment_series.size() ? b.segment_series[i] : 0;
        const ChartColor color = si < chart.series.size() ? chart.series[si].color
                                                          : ChartColor{128, 128, 128};
        cv::rectangle(image, {x0, yPx(axis, base + v)}, {x1, yPx(axis, base)}, bgr(color),
                      cv::FILLED);
        base += v;
      }
      if (!b.annotation.empty()) {
        text(image, b.annotation, {(x0 + x1) / 2, yPx(axis, base) - 6}, 0.4, kInk, true);
      }
      text(image, b.label, {(x0 + x1) / 2, kBottomPx + 18}, 0.38, kInk, true);
      x += slot_px;
    }
    text(image, g.label, {static_cast<int>((group_start + x) / 2), kBottomPx + 42}, 0.5, kInk,
         true);
    x += slot_px;
  }
  if (chart.reference_value >= 0.0) {
    const int y = yPx(axis, chart.reference_value);
    dashedLine(image, y, cv::Scalar(40, 40, 200));
    text(image, chart.reference_label, {kRightPx - 200, y - 6}, 0.42, cv::Scalar(40, 40, 200));
  }
  return image;
}

cv::Mat drawLineChart(const LineChart& chart) {
  cv::Mat image = canvas(chart.title);
  double x_lo = 1e300, x_hi = -1e300, y_lo = chart.y_from_zero ? 0.0 : 1e300, y_hi = -1e300;
  std::size_t points = 0;
  for (const LineSeries& s : chart.series) {
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      x_lo = std::min(x_lo, s.x[i]);
      x_hi = std::max(x_hi, s.x[i]);
      y_lo = std::min(y_lo, s.y[i]);
      y_hi = std::max(y_hi, s.y[i]);
      ++points;
    }
  }
  if (points == 0) {
    x_lo = 0.0, x_hi = 1.0, y_lo = 0.0, y_hi = 1.0;
  }
  const Axis ax = niceAxis(x_lo, x_hi);
  const Axis ay = niceAxis(y_lo, y_hi * 1.08);
  yAxis(image, ay, chart.y_label);
  for (double v = ax.min; v <= ax.max + 0.5 * ax.step; v += ax.step) {
    const int xp = xPx(ax, v);
    cv::line(image, {xp, kBottomPx}, {xp, kBottomPx + 5}, kInk, 1);
    text(image, formatTick(v), {xp, kBottomPx + 20}, 0.4, kInk, true);
  }
  text(image, chart.x_label, {(kLeftPx + kRightPx) / 2, kBottomPx + 45}, 0.45, kInk, true);
  std::vector<std::pair<std::string, ChartColor>> entries;
  for (const double x : chart.x_marks) {
    if (x < ax.min || x > ax.max) continue;
    cv::line(image, {xPx(ax, x), kTopPx}, {xPx(ax, x), kBottomPx}, bgr(kMarkColor), 1);
  }
  if (!chart.x_marks.empty() && !chart.x_marks_label.empty()) {
    entries.emplace_back(chart.x_marks_label, kMarkColor);
  }
  for (const LineSeries& s : chart.series) {
    entries.emplace_back(s.name, s.color);
    std::vector<cv::Point> polyline;
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      polyline.emplace_back(xPx(ax, s.x[i]), yPx(ay, s.y[i]));
    }
    if (polyline.size() > 1) {
      cv::polylines(image, polyline, false, bgr(s.color), 2, cv::LINE_AA);
    }
    if (!chart.point_markers) continue;
    for (const cv::Point& p : polyline) cv::circle(image, p, 4, bgr(s.color), cv::FILLED);
  }
  legend(image, entries);
  if (points == 0) {
    text(image, "no data", {(kLeftPx + kRightPx) / 2, (kTopPx + kBottomPx) / 2}, 0.7, kInk, true);
  }
  return image;
}

void writeChartPng(const cv::Mat& image, const std::string& path) {
  std::vector<std::uint8_t> png;
  if (!cv::imencode(".png", image, png)) throw Error("could not encode the chart " + path);
  writeFileAtomically(path, png);
}

}  // namespace strata::bench
