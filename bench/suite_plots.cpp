#include "suite_plots.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace strata::bench {
namespace {

using nlohmann::json;

/// report[a][b]... as a number, NaN where any step is missing or not a number.
double number(const json& j, std::initializer_list<const char*> path) {
  const json* at = &j;
  for (const char* key : path) {
    if (!at->is_object() || !at->contains(key)) return std::nan("");
    at = &(*at)[key];
  }
  return at->is_number() ? at->get<double>() : std::nan("");
}

std::string fixed(double v, int digits) {
  if (!std::isfinite(v)) return "-";
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.*f", digits, v);
  return buffer;
}

std::string voxelLabel(double voxel_size_m) { return fixed(voxel_size_m * 100.0, 0) + " cm"; }

const json& results(const json& report) {
  static const json kEmpty = json::array();
  return report.contains("results") && report["results"].is_array() ? report["results"] : kEmpty;
}

double median(const json& result, const char* side, const char* field) {
  return number(result, {side, field, "median"});
}

double zeroIfNan(double v) { return std::isfinite(v) ? v : 0.0; }

}  // namespace

BarChart fuseKernelChart(const json& report) {
  BarChart chart;
  chart.title = "TSDF fusion per frame (median), Strata kernels vs Open3D VoxelBlockGrid";
  chart.y_label = "ms per frame";
  chart.series = {{"upload", {150, 150, 150}},
                  {"normals + ranges", {86, 180, 233}},
                  {"allocate", {230, 159, 0}},
                  {"integrate", {0, 114, 178}},
                  {"Open3D (CPU)", {204, 121, 167}}};
  for (const json& r : results(report)) {
    ChartGroup group;
    group.label = voxelLabel(number(r, {"voxel_size_m"}));
    ChartBar strata;
    strata.label = "Strata";
    const char* kernels[] = {"upload_ms", "normals_ms", "allocate_ms", "integrate_ms"};
    for (std::size_t i = 0; i < 4; ++i) {
      strata.segments.push_back(zeroIfNan(median(r, "device", kernels[i])));
      strata.segment_series.push_back(i);
    }
    const double wall = median(r, "device", "wall_ms");
    strata.annotation = "wall " + fixed(wall, 1);
    group.bars.push_back(strata);
    const double open3d = number(r, {"open3d", "ms_per_frame", "median"});
    if (std::isfinite(open3d)) {
      ChartBar peer;
      peer.label = "Open3D";
      peer.segments = {open3d};
      peer.segment_series = {4};
      peer.annotation = fixed(wall / open3d, 2) + "x";
      group.bars.push_back(peer);
    }
    chart.groups.push_back(group);
  }
  return chart;
}

LineChart mapSizeChart(const std::vector<json>& reports, double voxel_size_m) {
  struct Point {
    double blocks, device_ms, wall_ms;
  };
  std::vector<Point> points;
  for (const json& report : reports) {
    const json* chosen = nullptr;
    for (const json& r : results(report)) {
      if (chosen == nullptr) chosen = &r;
      if (std::abs(number(r, {"voxel_size_m"}) - voxel_size_m) < 1e-6) chosen = &r;
    }
    if (chosen == nullptr) continue;
    const double blocks = number(*chosen, {"device", "blocks_allocated"});
    if (!std::isfinite(blocks)) continue;
    points.push_back({blocks, median(*chosen, "device", "device_total_ms"),
                      median(*chosen, "device", "wall_ms")});
  }
  std::sort(points.begin(), points.end(),
            [](const Point& a, const Point& b) { return a.blocks < b.blocks; });
  LineChart chart;
  chart.title = "Fusion time against map size (" + voxelLabel(voxel_size_m) +
                ", same frames, extra blocks far away)";
  chart.x_label = "blocks in the map";
  chart.y_label = "ms per frame";
  LineSeries device{"device (median)", {0, 114, 178}, {}, {}};
  LineSeries wall{"wall (median)", {213, 94, 0}, {}, {}};
  for (const Point& p : points) {
    if (std::isfinite(p.device_ms)) device.x.push_back(p.blocks), device.y.push_back(p.device_ms);
    if (std::isfinite(p.wall_ms)) wall.x.push_back(p.blocks), wall.y.push_back(p.wall_ms);
  }
  chart.series = {device, wall};
  return chart;
}

BarChart ceilingChart(const json& report) {
  BarChart chart;
  chart.title = "Integration voxel traffic / streaming ceiling (upper bound)";
  chart.y_label = "percent";
  chart.series = {{"integrate", {0, 114, 178}}};
  chart.reference_value = 60.0;
  chart.reference_label = "target 60 %";
  for (const json& r : results(report)) {
    const double fraction = number(r, {"integrate_vs_ceiling", "ceiling_fraction_upper"});
    if (!std::isfinite(fraction)) continue;
    ChartBar bar;
    bar.label = fixed(number(r, {"integrate_vs_ceiling", "integrate_gb_per_s_upper"}), 2) +
                " GB/s";
    bar.segments = {100.0 * fraction};
    bar.segment_series = {0};
    bar.annotation = fixed(100.0 * fraction, 1) + " %";
    chart.groups.push_back({voxelLabel(number(r, {"voxel_size_m"})), {bar}});
  }
  return chart;
}

std::string fuseMarkdownTable(const json& report) {
  std::string out =
      "| voxel | Strata wall ms | Strata device ms | Open3D ms | Strata/Open3D | upload | "
      "normals | allocate | integrate | ceiling |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const json& r : results(report)) {
    const double wall = median(r, "device", "wall_ms");
    const double open3d = number(r, {"open3d", "ms_per_frame", "median"});
    out += "| " + voxelLabel(number(r, {"voxel_size_m"})) + " | " + fixed(wall, 1) + " | " +
           fixed(median(r, "device", "device_total_ms"), 1) + " | " + fixed(open3d, 1) + " | " +
           fixed(wall / open3d, 2) + " | " + fixed(median(r, "device", "upload_ms"), 2) + " | " +
           fixed(median(r, "device", "normals_ms"), 2) + " | " +
           fixed(median(r, "device", "allocate_ms"), 2) + " | " +
           fixed(median(r, "device", "integrate_ms"), 2) + " | " +
           fixed(100.0 * number(r, {"integrate_vs_ceiling", "ceiling_fraction_upper"}), 1) +
           " % |\n";
  }
  return out;
}

}  // namespace strata::bench
