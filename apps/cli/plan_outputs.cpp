#include "cli/plan_outputs.h"

#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "cli/esdf_slice.h"
#include "cli/report_json.h"
#include "strata/core/atomic_file.h"
#include "strata/io/image_io.h"

namespace strata::apps {
namespace {

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
  Json j;
  j["planner"] = r.planner;
  j["success"] = r.result.success;
  j["message"] = r.result.message;
  j["length_m"] = r.result.length_m;
  j["min_clearance_m"] = r.result.min_clearance_m;
  j["planning_ms"] = r.result.planning_ms;
  j["build_ms"] = r.build_ms;
  j["collision_checks"] = r.result.collision_checks;
  j["memory_bytes"] = r.memory_bytes;
  j["start"] = jsonVector(r.request.start_W);
  j["goal"] = jsonVector(r.request.goal_W);
  j["radius_m"] = jsonFloat(r.request.radius_m);
  j["unknown"] = r.request.unknown == UnknownPolicy::kOccupied ? "occupied" : "free";
  j["waypoints"] = r.result.path_W.size();
  writeTextAtomically(path, jsonFileText(j));
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
