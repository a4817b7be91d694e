// The charts of `strata-bench all`: the figures they carry come from the report, and the drawn
// image shows them (bar heights proportional to the values, colours of the series).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "chart.h"
#include "suite_plots.h"

namespace strata::bench {
namespace {

using nlohmann::json;

json medianOf(double v) { return {{"mean", v + 1.0}, {"median", v}}; }

json fuseResult(double voxel_size_m, double integrate_ms, double open3d_ms, double blocks) {
  return {{"voxel_size_m", voxel_size_m},
          {"device",
           {{"upload_ms", medianOf(0.5)},
            {"normals_ms", medianOf(4.0)},
            {"allocate_ms", medianOf(3.0)},
            {"integrate_ms", medianOf(integrate_ms)},
            {"device_total_ms", medianOf(7.5 + integrate_ms)},
            {"wall_ms", medianOf(8.0 + integrate_ms)},
            {"blocks_allocated", blocks}}},
          {"integrate_vs_ceiling",
           {{"ceiling_fraction_upper", 0.25}, {"integrate_gb_per_s_upper", 1.5}}},
          {"open3d", open3d_ms > 0 ? json{{"ms_per_frame", medianOf(open3d_ms)}}
                                   : json("not built")}};
}

TEST(BenchPlots, KernelChartCarriesTheMediansAndTheRatio) {
  const json report = {{"results", {fuseResult(0.01, 20.0, 14.0, 5000),
                                    fuseResult(0.02, 8.0, 0.0, 2000)}}};
  const BarChart chart = fuseKernelChart(report);
  ASSERT_EQ(chart.groups.size(), 2u);
  EXPECT_EQ(chart.groups[0].label, "1 cm");
  ASSERT_EQ(chart.groups[0].bars.size(), 2u);  // Strata and Open3D
  const ChartBar& strata = chart.groups[0].bars[0];
  ASSERT_EQ(strata.segments.size(), 4u);
  EXPECT_DOUBLE_EQ(strata.segments[3], 20.0);  // median, not mean
  EXPECT_EQ(strata.annotation, "wall 28.0");
  EXPECT_EQ(chart.groups[0].bars[1].annotation, "2.00x");  // 28 ms / 14 ms
  EXPECT_EQ(chart.groups[1].bars.size(), 1u);  // no peer at 2 cm: no Open3D bar
}

TEST(BenchPlots, MapSizeChartSortsByBlocksAndPicksTheVoxelSize) {
  const json big = {{"results", {fuseResult(0.02, 9.0, 0.0, 40000)}}};
  const json small = {{"results", {fuseResult(0.01, 50.0, 0.0, 900),
                                   fuseResult(0.02, 8.0, 0.0, 2000)}}};
  const LineChart chart = mapSizeChart({big, small}, 0.02);
  ASSERT_EQ(chart.series.size(), 2u);
  const LineSeries& device = chart.series[0];
  ASSERT_EQ(device.x.size(), 2u);
  EXPECT_DOUBLE_EQ(device.x[0], 2000.0);
  EXPECT_DOUBLE_EQ(device.y[0], 15.5);
  EXPECT_DOUBLE_EQ(device.x[1], 40000.0);
}

TEST(BenchPlots, DrawnBarsAreAsTallAsTheirValues) {
  BarChart chart;
  chart.series = {{"a", {255, 0, 0}}, {"b", {0, 0, 255}}};
  chart.groups = {{"g", {{"x", {10.0}, {0}, ""}, {"y", {20.0}, {1}, ""}}}};
  const cv::Mat image = drawBarChart(chart);
  ASSERT_FALSE(image.empty());
  const auto columnHeight = [&](const cv::Vec3b& bgr) {
    int best = 0;
    for (int x = 0; x < image.cols; ++x) {
      int n = 0;
      for (int y = 0; y < image.rows; ++y) n += image.at<cv::Vec3b>(y, x) == bgr ? 1 : 0;
      best = std::max(best, n);
    }
    return best;
  };
  const int red = columnHeight({0, 0, 255});
  const int blue = columnHeight({255, 0, 0});
  ASSERT_GT(red, 20);  // the legend swatch alone is 13 px tall
  EXPECT_NEAR(static_cast<double>(blue) / red, 2.0, 0.1);
}

TEST(BenchPlots, EmptyReportsStillDraw) {
  EXPECT_FALSE(drawBarChart(fuseKernelChart(json::object())).empty());
  EXPECT_FALSE(drawLineChart(mapSizeChart({}, 0.02)).empty());
  EXPECT_NE(fuseMarkdownTable(json::object()).find("| voxel |"), std::string::npos);
}

}  // namespace
}  // namespace strata::bench
