#include "cli/topo_outputs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "cli/esdf_slice_font.h"
#include "cli/report_json.h"
#include "strata/core/atomic_file.h"
#include "strata/io/image_io.h"
#include "strata/plan/grid_astar.h"

namespace strata::apps {
namespace {

using plan::TopoMap;
using plan::TopoPortal;
using plan::VoxelBox;

constexpr int kMinMapPx = 640;
constexpr int kTitlePx = 28;

Eigen::Vector3f corner(const Eigen::Vector3i& v, float voxel_m) {
  return v.cast<float>() * voxel_m;
}

/// A distinct, fairly bright colour per cluster (golden-ratio hues).
cv::Scalar clusterColour(std::int32_t c) {
  const double hue = std::fmod(0.618033988749895 * c, 1.0) * 180.0;
  cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar(hue, 150 + 80 * (c % 2), 230 - 50 * (c / 2 % 2)));
  cv::Mat rgb;
  cv::cvtColor(hsv, rgb, cv::COLOR_HSV2RGB);
  const cv::Vec3b v = rgb.at<cv::Vec3b>(0, 0);
  return cv::Scalar(v[0], v[1], v[2]);
}

/// The voxel layer (global z index) holding the most cluster voxels.
int busiestLayer(const TopoMap& topo) {
  std::vector<std::int64_t> count(
      static_cast<std::size_t>(topo.bounds().hi.z() - topo.bounds().lo.z() + 1), 0);
  for (const VoxelBox& b : topo.clusters()) {
    const std::int64_t area =
        static_cast<std::int64_t>(b.hi.x() - b.lo.x() + 1) * (b.hi.y() - b.lo.y() + 1);
    for (int z = b.lo.z(); z <= b.hi.z(); ++z)
      count[static_cast<std::size_t>(z - topo.bounds().lo.z())] += area;
  }
  return topo.bounds().lo.z() +
         static_cast<int>(std::max_element(count.begin(), count.end()) - count.begin());
}

Json clustersJson(const TopoMap& topo) {
  const float voxel_m = topo.voxelSize();
  Json clusters = Json::array();
  for (std::size_t c = 0; c < topo.clusters().size(); ++c) {
    const VoxelBox& b = topo.clusters()[c];
    Json j;
    j["id"] = c;
    j["min_m"] = jsonVector(corner(b.lo, voxel_m));
    j["max_m"] = jsonVector(corner(b.hi + Eigen::Vector3i::Ones(), voxel_m));
    j["voxels"] = b.volume();
    clusters.push_back(std::move(j));
  }
  return clusters;
}

Json portalsJson(const TopoMap& topo) {
  Json portals = Json::array();
  for (std::size_t i = 0; i < topo.portals().size(); ++i) {
    const TopoPortal& p = topo.portals()[i];
    Json j;
    j["id"] = i;
    j["clusters"] = Json::array({p.a, p.b});
    j["axis"] = p.axis;
    j["min_m"] = jsonVector(p.lo_W);
    j["max_m"] = jsonVector(p.hi_W);
    portals.push_back(std::move(j));
  }
  return portals;
}

/// Every pair of portals of one cluster: [portal, portal, straight-line length in metres].
Json edgesJson(const TopoMap& topo) {
  Json edges = Json::array();
  for (std::size_t c = 0; c < topo.clusters().size(); ++c) {
    const auto cluster = static_cast<std::int32_t>(c);
    for (const std::int32_t* i = topo.portalsBegin(cluster); i != topo.portalsEnd(cluster); ++i) {
      for (const std::int32_t* j = i + 1; j != topo.portalsEnd(cluster); ++j) {
        const float length_m = (topo.portals()[static_cast<std::size_t>(*i)].centre() -
                                topo.portals()[static_cast<std::size_t>(*j)].centre())
                                   .norm();
        edges.push_back(Json::array({*i, *j, jsonFloat(length_m)}));
      }
    }
  }
  return edges;
}

}  // namespace

std::size_t gridMemoryBytes(const TopoMap& topo) {
  return topo.stats().grid_cells * plan::kGridAStarBytesPerCell;
}

void writeTopoJson(const std::string& path, const TopoMap& topo) {
  const plan::TopoStats& s = topo.stats();
  Json j;
  j["radius_m"] = jsonFloat(topo.options().radius_m);
  j["unknown"] = topo.options().unknown == UnknownPolicy::kOccupied ? "occupied" : "free";
  j["voxel_size_m"] = jsonFloat(topo.voxelSize());
  j["build_ms"] = s.build_ms;
  j["traversable_voxels"] = s.traversable_voxels;
  j["grid_cells"] = s.grid_cells;
  j["cluster_count"] = topo.clusters().size();
  j["portal_count"] = topo.portals().size();
  j["edge_count"] = topo.edgeCount();
  j["memory_bytes"] = topo.memoryBytes();
  j["grid_memory_bytes"] = gridMemoryBytes(topo);
  j["clusters"] = clustersJson(topo);
  j["portals"] = portalsJson(topo);
  j["edges"] = edgesJson(topo);
  writeTextAtomically(path, jsonFileText(j));
}

float writeTopoPng(const std::string& path, const TopoMap& topo, float z_m) {
  const float voxel_m = topo.voxelSize();
  const VoxelBox& bounds = topo.bounds();
  const int kz =
      std::isfinite(z_m) ? static_cast<int>(std::floor(z_m / voxel_m)) : busiestLayer(topo);
  const int nx = bounds.hi.x() - bounds.lo.x() + 1, ny = bounds.hi.y() - bounds.lo.y() + 1;
  const int ppv =
      std::clamp((kMinMapPx + std::max(nx, ny) - 1) / std::max(1, std::max(nx, ny)), 1, 16);
  cv::Mat image(kTitlePx + ny * ppv, nx * ppv, CV_8UC3, cv::Scalar(215, 215, 215));
  const auto px = [&](float x_m, float y_m) {
    return cv::Point(
        static_cast<int>(std::lround((x_m / voxel_m - bounds.lo.x()) * ppv)),
        kTitlePx + static_cast<int>(std::lround((ny - (y_m / voxel_m - bounds.lo.y())) * ppv)));
  };
  cv::rectangle(image, cv::Rect(0, kTitlePx, nx * ppv, ny * ppv), cv::Scalar(70, 70, 70),
                cv::FILLED);
  for (std::size_t c = 0; c < topo.clusters().size(); ++c) {
    const VoxelBox& b = topo.clusters()[c];
    if (kz < b.lo.z() || kz > b.hi.z()) continue;
    const cv::Point p0 = px(b.lo.x() * voxel_m, (b.hi.y() + 1) * voxel_m);
    const cv::Point p1 = px((b.hi.x() + 1) * voxel_m, b.lo.y() * voxel_m);
    cv::rectangle(image, cv::Rect(p0, p1), clusterColour(static_cast<std::int32_t>(c)), cv::FILLED);
  }
  for (const TopoPortal& p : topo.portals()) {
    // Portals crossing this layer on a vertical plane: a line along the shared face.
    const float z_lo = p.lo_W.z() / voxel_m - 0.5f, z_hi = p.hi_W.z() / voxel_m - 0.5f;
    if (p.axis == 2 || kz < std::lround(z_lo) || kz > std::lround(z_hi)) continue;
    const float h = 0.5f * voxel_m;
    const Eigen::Vector3f lo =
        p.lo_W - Eigen::Vector3f(p.axis == 0 ? 0 : h, p.axis == 1 ? 0 : h, 0);
    const Eigen::Vector3f hi =
        p.hi_W + Eigen::Vector3f(p.axis == 0 ? 0 : h, p.axis == 1 ? 0 : h, 0);
    cv::line(image, px(lo.x(), lo.y()), px(hi.x(), hi.y()), cv::Scalar(255, 255, 255),
             std::max(1, ppv / 3), cv::LINE_AA);
  }
  ColorImage out(image.cols, image.rows, 255);
  std::copy(image.datastart, image.dataend, out.rgb.begin());
  char title[160];
  std::snprintf(
      title, sizeof(title), "TOPOLOGICAL MAP AT Z=%.2f M: %zu CLUSTERS, %zu PORTALS (WHITE)",
      static_cast<double>((kz + 0.5f) * voxel_m), topo.clusters().size(), topo.portals().size());
  const int scale = textWidth(title, 2) <= out.width_px - 12 ? 2 : 1;
  drawText(out, 6, 6, title, scale, {{20, 20, 20}});
  writeColorPng(path, out);
  return (static_cast<float>(kz) + 0.5f) * voxel_m;
}

}  // namespace strata::apps
