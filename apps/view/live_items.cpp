#include "view/live_items.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "strata/core/error.h"
#include "strata/lcm/esdf_slice_msg.h"

namespace strata::view {

std::string blockId(const std::int32_t index[3]) {
  return "block:" + std::to_string(index[0]) + "," + std::to_string(index[1]) + "," +
         std::to_string(index[2]);
}

Mesh messageMesh(const std::vector<std::vector<float>>& vertices,
                 const std::vector<std::vector<std::int32_t>>& triangles, const char* what,
                 const Eigen::Isometry3d& T) {
  Mesh mesh;
  mesh.vertices.reserve(vertices.size());
  for (const auto& v : vertices) {
    const Eigen::Vector3d p = T * Eigen::Vector3d(v.at(0), v.at(1), v.at(2));
    if (!p.allFinite()) throw InputError(std::string(what) + ": a vertex is not finite");
    mesh.vertices.push_back(p.cast<float>());
  }
  const auto n = static_cast<std::int64_t>(vertices.size());
  mesh.triangles.reserve(triangles.size());
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      if (t.at(k) < 0 || t.at(k) >= n) {
        throw InputError(std::string(what) + ": triangle index " + std::to_string(t.at(k)) +
                         " outside its " + std::to_string(n) + " vertices");
      }
    }
    mesh.triangles.emplace_back(t[0], t[1], t[2]);
  }
  return mesh;
}

Mesh blockMesh(const mesh_block_t& block) {
  Mesh mesh = messageMesh(block.vertices, block.triangles, "mesh block");
  mesh.colors.reserve(block.colors.size());
  for (const auto& c : block.colors) mesh.colors.push_back({c.at(0), c.at(1), c.at(2)});
  return mesh;
}

void meshBounds(const Mesh& mesh, Eigen::Vector3f* min_W, Eigen::Vector3f* max_W) {
  *min_W = Eigen::Vector3f::Constant(std::numeric_limits<float>::max());
  *max_W = -*min_W;
  for (const auto& v : mesh.vertices) {
    *min_W = min_W->cwiseMin(v);
    *max_W = max_W->cwiseMax(v);
  }
  if (mesh.vertices.empty()) *min_W = *max_W = Eigen::Vector3f::Zero();
}

EsdfSliceImage sliceImage(const esdf_slice_t& s) {
  if (!std::isfinite(s.resolution_m) || s.resolution_m <= 0.0f) {
    throw InputError("esdf_slice_t: resolution " + std::to_string(s.resolution_m) + " m");
  }
  if (!std::isfinite(s.z_m) || !std::isfinite(s.origin_x_m) || !std::isfinite(s.origin_y_m)) {
    throw InputError("esdf_slice_t: height or origin not finite");
  }
  EsdfSliceImage image;
  image.z_m = s.z_m;
  image.resolution_m = s.resolution_m;
  image.origin_x_m = s.origin_x_m - 0.5f * s.resolution_m;
  image.origin_y_m = s.origin_y_m - 0.5f * s.resolution_m;
  image.width = s.width;
  image.height = s.height;
  image.distances_m.assign(static_cast<std::size_t>(s.width) * s.height,
                           std::numeric_limits<float>::quiet_NaN());
  for (int r = 0; r < s.height; ++r) {
    for (int c = 0; c < s.width; ++c) {
      const float d = s.distance_m.at(r).at(c);
      if (s.state.at(r).at(c) != lcm_io::kSliceObserved || !std::isfinite(d)) continue;
      image.distances_m[static_cast<std::size_t>(r) * s.width + c] = d;
      image.max_m = std::max(image.max_m, d);
    }
  }
  return image;
}

std::optional<float> sliceDistance(const EsdfSliceImage& s, float x_m, float y_m) {
  const float u = (x_m - s.origin_x_m) / s.resolution_m;  // in cells from the corner
  const float v = (y_m - s.origin_y_m) / s.resolution_m;
  if (!(u >= 0.0f && v >= 0.0f && u < s.width && v < s.height)) return std::nullopt;
  const auto at = [&s](int r, int c) {
    return s.distances_m[static_cast<std::size_t>(r) * s.width + c];
  };
  // Bilinear between the centres of the four cells around the point.
  const int c0 = static_cast<int>(std::floor(u - 0.5f));
  const int r0 = static_cast<int>(std::floor(v - 0.5f));
  if (c0 >= 0 && r0 >= 0 && c0 + 1 < s.width && r0 + 1 < s.height) {
    const float a = at(r0, c0), b = at(r0, c0 + 1), c = at(r0 + 1, c0), d = at(r0 + 1, c0 + 1);
    if (std::isfinite(a) && std::isfinite(b) && std::isfinite(c) && std::isfinite(d)) {
      const float fx = u - 0.5f - c0, fy = v - 0.5f - r0;
      return (1 - fy) * ((1 - fx) * a + fx * b) + fy * ((1 - fx) * c + fx * d);
    }
  }
  const float nearest = at(static_cast<int>(v), static_cast<int>(u));
  if (!std::isfinite(nearest)) return std::nullopt;
  return nearest;
}

nlohmann::json statsValues(const map_stats_t& s) {
  return {{"blocks", s.blocks},
          {"frames", s.frames_fused},
          {"frames received", s.frames_received},
          {"dropped", s.frames_dropped_backlog + s.frames_dropped_no_pose},
          {"rejected", s.frames_rejected},
          {"session", s.session},
          {"session open", s.session_active != 0},
          {"device MB", static_cast<double>(s.device_bytes) / 1e6},
          {"fuse ms", s.fuse_ms_last},
          {"queue", s.queue_depth},
          {"mapper bad messages", s.messages_bad}};
}

}  // namespace strata::view
