#pragma once
// Small charts for benchmark reports, drawn with OpenCV into a BGR image: grouped (optionally
// stacked) bars and x/y line charts, with axes, ticks, a legend and an optional reference line.
// Pure functions of their input; no I/O (writeChartPng does the file).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace strata::bench {

using ChartColor = std::array<std::uint8_t, 3>;  // R, G, B

struct ChartSeries {
  std::string name;
  ChartColor color;
};

/// One bar: segments stacked bottom to top, segment i drawn in series[segment_series[i]].
struct ChartBar {
  std::string label;                     // under the bar
  std::vector<double> segments;          // >= 0, in the chart's unit
  std::vector<std::size_t> segment_series;
  std::string annotation;                // above the bar (e.g. a ratio); may be empty
};

struct ChartGroup {
  std::string label;  // under the group
  std::vector<ChartBar> bars;
};

struct BarChart {
  std::string title;
  std::string y_label;
  std::vector<ChartSeries> series;  // the legend
  std::vector<ChartGroup> groups;
  double reference_value = -1.0;    // a dashed horizontal line where >= 0
  std::string reference_label;
};

struct LineSeries {
  std::string name;
  ChartColor color;
  std::vector<double> x;
  std::vector<double> y;  // same length as x
};

struct LineChart {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<LineSeries> series;
  bool y_from_zero = true;
  /// A dot on every point (false for long time series, where dots hide the line).
  bool point_markers = true;
  /// Thin vertical lines at these x values (events, e.g. session boundaries), labelled in the
  /// legend by x_marks_label when not empty.
  std::vector<double> x_marks;
  std::string x_marks_label;
};

/// 960x540 images. Empty charts (no bars or no points) draw the axes and "no data".
cv::Mat drawBarChart(const BarChart& chart);
cv::Mat drawLineChart(const LineChart& chart);

/// Encodes `image` as PNG and writes it atomically; Error naming the path on failure.
void writeChartPng(const cv::Mat& image, const std::string& path);

/// "1.5", "20", "0.25": a tick label with at most 3 significant digits.
std::string formatTick(double value);

}  // namespace strata::bench
