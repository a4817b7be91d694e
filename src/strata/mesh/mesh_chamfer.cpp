// meshChamferDistance with a uniform hash grid: points are bucketed by cell; a query scans shells
// of cells around its own, nearest first, until no unscanned cell can hold a closer point.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <unordered_map>
#include <utility>
#include <vector>

#include "strata/core/error.h"
#include "strata/mesh/mesh_metrics.h"

namespace strata {
namespace {

class VertexGrid {
 public:
  VertexGrid(const std::vector<Eigen::Vector3f>& points, float cell_m);
  float nearestDistance(const Eigen::Vector3f& q) const;

 private:
  Eigen::Vector3i cellOf(const Eigen::Vector3f& p) const {
    // Clamped so far-away queries cannot overflow; such cells simply lie outside the grid.
    const float limit = static_cast<float>(1 << 22);
    return ((p - origin_) / cell_m_).array().floor().max(-limit).min(limit).cast<int>();
  }
  std::uint64_t key(const Eigen::Vector3i& c) const {
    return static_cast<std::uint64_t>(c.x()) | static_cast<std::uint64_t>(c.y()) << 21 |
           static_cast<std::uint64_t>(c.z()) << 42;
  }
  void scanCell(const Eigen::Vector3i& c, const Eigen::Vector3f& q, float& best_sq) const;

  const std::vector<Eigen::Vector3f>& points_;
  Eigen::Vector3f origin_;
  float cell_m_;
  Eigen::Vector3i dims_;
  std::vector<std::uint32_t> order_;  // point indices sorted by cell key
  std::unordered_map<std::uint64_t, std::pair<std::uint32_t, std::uint32_t>> ranges_;
};

VertexGrid::VertexGrid(const std::vector<Eigen::Vector3f>& points, float cell_m)
    : points_(points), origin_(points[0]) {
  Eigen::Vector3f upper = points[0];
  for (const Eigen::Vector3f& p : points) {
    origin_ = origin_.cwiseMin(p);
    upper = upper.cwiseMax(p);
  }
  // Keep cell coordinates within 21 bits per axis.
  cell_m_ = std::max({cell_m, (upper - origin_).maxCoeff() / float(1 << 20), 1e-9f});
  dims_ = cellOf(upper) + Eigen::Vector3i::Ones();
  std::vector<std::uint64_t> keys(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) keys[i] = key(cellOf(points[i]));
  order_.resize(points.size());
  std::iota(order_.begin(), order_.end(), 0u);
  std::sort(order_.begin(), order_.end(),
            [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
  for (std::uint32_t i = 0; i < order_.size();) {
    std::uint32_t end = i;
    while (end < order_.size() && keys[order_[end]] == keys[order_[i]]) ++end;
    ranges_[keys[order_[i]]] = {i, end};
    i = end;
  }
}

void VertexGrid::scanCell(const Eigen::Vector3i& c, const Eigen::Vector3f& q,
                          float& best_sq) const {
  const auto it = ranges_.find(key(c));
  if (it == ranges_.end()) return;
  for (std::uint32_t i = it->second.first; i < it->second.second; ++i) {
    best_sq = std::min(best_sq, (points_[order_[i]] - q).squaredNorm());
  }
}

float VertexGrid::nearestDistance(const Eigen::Vector3f& q) const {
  const Eigen::Vector3i qc = cellOf(q);
  // Shell r holds the cells at Chebyshev distance r from qc; those beyond it are >= r cells away.
  const Eigen::Vector3i top = dims_ - Eigen::Vector3i::Ones();
  const int outside = std::max({0, (-qc).maxCoeff(), (qc - top).maxCoeff()});
  const int last = std::max(qc.cwiseAbs().maxCoeff(), (qc - top).cwiseAbs().maxCoeff());
  float best_sq = std::numeric_limits<float>::infinity();
  for (int r = outside; r <= last; ++r) {
    const Eigen::Vector3i lo = (qc.array() - r).max(0);
    const Eigen::Vector3i hi = (qc.array() + r).min(top.array());
    for (int z = lo.z(); z <= hi.z(); ++z) {
      for (int y = lo.y(); y <= hi.y(); ++y) {
        for (int x = lo.x(); x <= hi.x(); ++x) {
          const Eigen::Vector3i c(x, y, z);
          if ((c - qc).cwiseAbs().maxCoeff() == r) scanCell(c, q, best_sq);
        }
      }
    }
    const float reach = static_cast<float>(r) * cell_m_;
    if (best_sq <= reach * reach) break;
  }
  return std::sqrt(best_sq);
}

float meanEdgeLength(const Mesh& mesh) {
  double sum = 0.0;
  for (const Eigen::Vector3i& tri : mesh.triangles) {
    sum += (mesh.vertices[tri[0]] - mesh.vertices[tri[1]]).norm();
  }
  return mesh.triangles.empty() ? 0.0f : static_cast<float>(sum / mesh.triangles.size());
}

double meanNearestDistance(const Mesh& from, const Mesh& to) {
  float cell_m = 2.0f * meanEdgeLength(to);
  if (cell_m <= 0.0f) {  // a point cloud: about one point per cell of its bounding box
    Eigen::Vector3f lo = to.vertices[0], hi = to.vertices[0];
    for (const Eigen::Vector3f& p : to.vertices) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    cell_m = (hi - lo).maxCoeff() / std::cbrt(static_cast<float>(to.vertices.size()));
  }
  const VertexGrid grid(to.vertices, cell_m);
  double sum = 0.0;
  for (const Eigen::Vector3f& p : from.vertices) sum += grid.nearestDistance(p);
  return sum / static_cast<double>(from.vertices.size());
}

}  // namespace

double meshChamferDistance(const Mesh& a, const Mesh& b) {
  if (a.vertices.empty() || b.vertices.empty()) {
    throw InputError("meshChamferDistance: a mesh has no vertices");
  }
  return 0.5 * (meanNearestDistance(a, b) + meanNearestDistance(b, a));
}

}  // namespace strata
