#include "strata/change/eval/internal/evaluation_surface_index.h"

#include <algorithm>
#include <cmath>

#include "strata/core/error.h"
#include "strata/sim/world/triangle_distance.h"

namespace strata::change {

SurfaceIndex::SurfaceIndex(float max_query_m) : cell_m_(max_query_m) {
  if (!std::isfinite(max_query_m) || max_query_m <= 0.0f) {
    throw InputError("SurfaceIndex: max_query_m must be positive");
  }
}

std::uint64_t SurfaceIndex::cellKey(const Eigen::Vector3i& c) const {
  // 21 bits per axis with a bias: +-2^20 cells, far beyond any room at centimetre cells.
  constexpr std::int64_t kBias = 1 << 20;
  const auto x = static_cast<std::uint64_t>(c.x() + kBias) & 0x1FFFFF;
  const auto y = static_cast<std::uint64_t>(c.y() + kBias) & 0x1FFFFF;
  const auto z = static_cast<std::uint64_t>(c.z() + kBias) & 0x1FFFFF;
  return x | (y << 21) | (z << 42);
}

Eigen::Vector3i SurfaceIndex::cellOf(const Eigen::Vector3f& p) const {
  return (p / cell_m_).array().floor().cast<int>();
}

void SurfaceIndex::add(const Mesh& mesh, int tag) {
  for (const Eigen::Vector3i& t : mesh.triangles) {
    Triangle tri{mesh.vertices[static_cast<std::size_t>(t[0])].cast<double>(),
                 mesh.vertices[static_cast<std::size_t>(t[1])].cast<double>(),
                 mesh.vertices[static_cast<std::size_t>(t[2])].cast<double>(), tag};
    const auto id = static_cast<std::uint32_t>(triangles_.size());
    triangles_.push_back(tri);
    // Register in every cell the triangle's bounding box touches; a query then only needs the
    // cells around its own (max_m <= cell edge).
    const Eigen::Vector3f lo = tri.a.cwiseMin(tri.b).cwiseMin(tri.c).cast<float>();
    const Eigen::Vector3f hi = tri.a.cwiseMax(tri.b).cwiseMax(tri.c).cast<float>();
    const Eigen::Vector3i c0 = cellOf(lo), c1 = cellOf(hi);
    for (int z = c0.z(); z <= c1.z(); ++z) {
      for (int y = c0.y(); y <= c1.y(); ++y) {
        for (int x = c0.x(); x <= c1.x(); ++x) cells_[cellKey({x, y, z})].push_back(id);
      }
    }
  }
}

bool SurfaceIndex::nearest(const Eigen::Vector3f& p, float max_m, Hit& hit) const {
  const Eigen::Vector3i c = cellOf(p);
  const Eigen::Vector3d pd = p.cast<double>();
  double best = std::min(max_m, cell_m_);
  bool found = false;
  for (int dz = -1; dz <= 1; ++dz) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const auto it = cells_.find(cellKey(c + Eigen::Vector3i(dx, dy, dz)));
        if (it == cells_.end()) continue;
        for (const std::uint32_t id : it->second) {
          const Triangle& t = triangles_[id];
          const double d = (sim::closestPointOnTriangle(pd, t.a, t.b, t.c) - pd).norm();
          if (d <= best) {
            best = d;
            hit = {static_cast<float>(d), t.tag};
            found = true;
          }
        }
      }
    }
  }
  return found;
}

double shareWithin(const std::vector<Eigen::Vector3f>& points, const SurfaceIndex& surface,
                   float distance_m) {
  if (points.empty()) return 0.0;
  const auto hits = std::count_if(points.begin(), points.end(), [&](const Eigen::Vector3f& p) {
    return surface.within(p, distance_m);
  });
  return static_cast<double>(hits) / static_cast<double>(points.size());
}

}  // namespace strata::change
