#include "soak_chart.h"

#include <string>

#include "chart.h"

namespace strata::bench {
namespace {

constexpr ChartColor kRssColor = {31, 119, 180};
constexpr ChartColor kPeakColor = {255, 127, 14};
constexpr ChartColor kDeviceColor = {44, 160, 44};
// At most this many session lines: hundreds of sessions a few pixels apart fill a panel grey.
constexpr std::size_t kMaxMarks = 40;

/// Every n-th session end (n = 1 while they are few), and the legend entry that says which.
std::vector<double> thinnedMarks(const std::vector<double>& ends_s, std::string* label) {
  const std::size_t every = (ends_s.size() + kMaxMarks - 1) / kMaxMarks;
  if (every <= 1) {
    *label = "session end";
    return ends_s;
  }
  *label = "every " + std::to_string(every) + "th session end";
  std::vector<double> kept;
  for (std::size_t i = every - 1; i < ends_s.size(); i += every) kept.push_back(ends_s[i]);
  return kept;
}

LineChart timeChart(const std::string& title, const std::string& y_label,
                    const std::vector<double>& session_ends_s) {
  LineChart chart;
  chart.title = title;
  chart.x_label = "elapsed, s";
  chart.y_label = y_label;
  chart.point_markers = false;  // one point a second
  chart.x_marks = thinnedMarks(session_ends_s, &chart.x_marks_label);
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
