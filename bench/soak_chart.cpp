#include "soak_chart.h"

#include "chart.h"

namespace strata::bench {
namespace {

constexpr ChartColor kRssColor = {31, 119, 180};
constexpr ChartColor kPeakColor = {255, 127, 14};
constexpr ChartColor kDeviceColor = {44, 160, 44};

LineChart timeChart(const std::string& title, const std::string& y_label,
                    const std::vector<double>& session_ends_s) {
  LineChart chart;
  chart.title = title;
  chart.x_label = "elapsed, s";
  chart.y_label = y_label;
  chart.point_markers = false;  // one point a second
  chart.x_marks = session_ends_s;
  chart.x_marks_label = "session end";
  return chart;
}

}  // namespace

cv::Mat drawSoakChart(const SoakSeries& s, const std::vector<double>& session_ends_s) {
  LineChart host = timeChart("strata-mapper resident memory", "MiB", session_ends_s);
  host.y_from_zero = false;  // growth of a few MiB on hundreds must show
  host.series.push_back({"VmRSS", kRssColor, s.t_s, s.rss_mib});
  host.series.push_back({"VmHWM (peak)", kPeakColor, s.t_s, s.hwm_mib});
  LineChart device =
      timeChart("strata-mapper device memory (Vulkan buffers)", "MiB", session_ends_s);
  device.series.push_back({"device buffers", kDeviceColor, s.t_s, s.device_mib});
  cv::Mat image;
  cv::vconcat(drawLineChart(host), drawLineChart(device), image);
  return image;
}

}  // namespace strata::bench
