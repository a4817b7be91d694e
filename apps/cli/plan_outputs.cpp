#include "cli/plan_outputs.h"

#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "cli/esdf_slice.h"
#include "core/atomic_file.h"
#include "core/json_text.h"
#include "io/image_io.h"

namespace strata::apps {
namespace {

std::string point(const Eigen::Vector3f& p) {
  return "[" + jsonNumber(p.x()) + ", " + jsonNumber(p.y()) + ", " + jsonNumber(p.z()) + "]";
}

float meanHeight(const PlanReport& r) {
  if (r.result.path_W.empty()) return 0.5f * (r.request.start_W.z() + r.request.goal_W.z());
  float sum = 0.0f;
  for (const Eigen::Vector3f& p : r.result.path_W) sum += p.z();
  return sum / static_cast<float>(r.result.path_W.size());
}

cv::Point pixel(const EsdfSliceStats& s, float voxel_m, const Eigen::Vector3f& p) {
  const Eigen::Vector2f px = slicePixel(s, voxel_m, p.x(), p.y());
  return cv::Point(static_cast<int>(std::lround(px.x())), static_cast<int>(std::lround(px.y())));
}

}  // namespace

void writePathCsv(const std::string& path, const std::vector<Eigen::Vector3f>& path_W) {
  std::ostringstream out;
  out << "x,y,z\n";
  char line[96];
  for (const Eigen::Vector3f& p : path_W) {
    std::snprintf(line, sizeof(line), "%.4f,%.4f,%.4f\n", static_cast<double>(p.x()),
                  static_cast<double>(p.y()), static_cast<double>(p.z()));
    out << line;
  }
  writeTextAtomically(path, out.str());
}

void writePlanReport(const std::string& path, const PlanReport& r) {
  std::ostringstream out;
  out << "{\n  \"planner\": " << jsonQuoted(r.planner)
      << ",\n  \"success\": " << (r.result.success ? "true" : "false")
      << ",\n  \"message\": " << jsonQuoted(r.result.message)
      << ",\n  \"length_m\": " << jsonNumber(r.result.length_m)
      << ",\n  \"min_clearance_m\": " << jsonNumber(r.result.min_clearance_m)
      << ",\n  \"planning_ms\": " << jsonNumber(r.result.planning_ms)
      << ",\n  \"build_ms\": " << jsonNumber(r.build_ms)
      << ",\n  \"collision_checks\": " << r.result.collision_checks
      << ",\n  \"memory_bytes\": " << r.memory_bytes
      << ",\n  \"start\": " << point(r.request.start_W)
      << ",\n  \"goal\": " << point(r.request.goal_W)
      << ",\n  \"radius_m\": " << jsonNumber(r.request.radius_m) << ",\n  \"unknown\": "
      << (r.request.unknown == UnknownPolicy::kOccupied ? "\"occupied\"" : "\"free\"")
      << ",\n  \"waypoints\": " << r.result.path_W.size() << "\n}\n";
  writeTextAtomically(path, out.str());
}

void writePathPng(const std::string& path, const EsdfMap& esdf, const PlanReport& r) {
  EsdfSliceOptions options;
  options.z_m = meanHeight(r);
  options.max_distance_m = esdf.config.max_distance_m;
  char title[160];
  std::snprintf(title, sizeof(title), "%s PATH OVER THE ESDF AT Z=%.2f M: %s, RADIUS %.2f M",
                r.planner.c_str(), static_cast<double>(options.z_m),
                r.result.success ? (std::to_string(r.result.length_m).substr(0, 5) + " M").c_str()
                                 : "NO PATH",
                static_cast<double>(r.request.radius_m));
  options.title = title;
  EsdfSlice slice = renderEsdfSlice(esdf, options);
  cv::Mat image(slice.image.height_px, slice.image.width_px, CV_8UC3, slice.image.rgb.data());
  const float voxel_m = esdf.voxel_size_m;
  const int thickness = std::max(2, slice.stats.pixels_per_voxel / 2);
  for (std::size_t i = 1; i < r.result.path_W.size(); ++i) {
    cv::line(image, pixel(slice.stats, voxel_m, r.result.path_W[i - 1]),
             pixel(slice.stats, voxel_m, r.result.path_W[i]), cv::Scalar(255, 255, 255),
             thickness + 2, cv::LINE_AA);
    cv::line(image, pixel(slice.stats, voxel_m, r.result.path_W[i - 1]),
             pixel(slice.stats, voxel_m, r.result.path_W[i]), cv::Scalar(240, 40, 200), thickness,
             cv::LINE_AA);
  }
  const int mark = 3 * thickness;
  // The image is RGB: scalars are (R, G, B).
  cv::circle(image, pixel(slice.stats, voxel_m, r.request.start_W), mark, cv::Scalar(20, 200, 40),
             cv::FILLED, cv::LINE_AA);
  cv::circle(image, pixel(slice.stats, voxel_m, r.request.goal_W), mark, cv::Scalar(220, 30, 30),
             cv::FILLED, cv::LINE_AA);
  writeColorPng(path, slice.image);
}

}  // namespace strata::apps
