#include "strata/occupancy/eval/occupancy_nearest.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "strata/core/error.h"

namespace strata::eval {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

Eigen::Vector3i cellOf(const Eigen::Vector3f& p, float cell_m) {
  return (p / cell_m).array().floor().cast<int>().matrix();
}

std::uint64_t cellKey(const Eigen::Vector3i& c) {
  constexpr std::int64_t kBias = 1 << 20;
  const auto x = static_cast<std::uint64_t>(c.x() + kBias) & 0x1FFFFF;
  const auto y = static_cast<std::uint64_t>(c.y() + kBias) & 0x1FFFFF;
  const auto z = static_cast<std::uint64_t>(c.z() + kBias) & 0x1FFFFF;
  return x | (y << 21) | (z << 42);
}

void requireRadius(float radius_m) {
  if (!(radius_m > 0.0f) || !std::isfinite(radius_m)) {
    throw InputError("nearest-neighbour grid: radius must be finite and positive");
  }
}

/// Calls visit(cell key) for the 27 cells around q's cell (enough: cell edge = radius).
template <typename Visit>
void forNeighbourCells(const Eigen::Vector3f& q, float cell_m, Visit visit) {
  const Eigen::Vector3i c = cellOf(q, cell_m);
  for (int dz = -1; dz <= 1; ++dz) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) visit(cellKey(c + Eigen::Vector3i(dx, dy, dz)));
    }
  }
}

}  // namespace

PointGrid::PointGrid(std::vector<Eigen::Vector3f> points, float radius_m)
    : points_(std::move(points)), cell_m_(radius_m) {
  requireRadius(radius_m);
  for (std::size_t i = 0; i < points_.size(); ++i) {
    cells_[cellKey(cellOf(points_[i], cell_m_))].push_back(static_cast<std::uint32_t>(i));
  }
}

double PointGrid::nearestWithin(const Eigen::Vector3f& q) const {
  double best = kInfinity;
  forNeighbourCells(q, cell_m_, [&](std::uint64_t key) {
    const auto it = cells_.find(key);
    if (it == cells_.end()) return;
    for (const std::uint32_t i : it->second) best = std::min(best, (points_[i] - q).norm() * 1.0);
  });
  return best <= cell_m_ ? best : kInfinity;
}

TriangleGrid::TriangleGrid(const Mesh& mesh, float radius_m) : mesh_(mesh), cell_m_(radius_m) {
  requireRadius(radius_m);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Eigen::Vector3i& tri = mesh.triangles[t];
    Eigen::Vector3f lo = mesh.vertices[tri[0]], hi = lo;
    for (int k = 1; k < 3; ++k) {
      lo = lo.cwiseMin(mesh.vertices[tri[k]]);
      hi = hi.cwiseMax(mesh.vertices[tri[k]]);
    }
    const Eigen::Vector3i a = cellOf(lo, cell_m_), b = cellOf(hi, cell_m_);
    for (int z = a.z(); z <= b.z(); ++z) {
      for (int y = a.y(); y <= b.y(); ++y) {
        for (int x = a.x(); x <= b.x(); ++x) {
          cells_[cellKey(Eigen::Vector3i(x, y, z))].push_back(static_cast<std::uint32_t>(t));
        }
      }
    }
  }
}

double TriangleGrid::nearestWithin(const Eigen::Vector3f& q) const {
  double best = kInfinity;
  forNeighbourCells(q, cell_m_, [&](std::uint64_t key) {
    const auto it = cells_.find(key);
    if (it == cells_.end()) return;
    for (const std::uint32_t t : it->second) {
      const Eigen::Vector3i& tri = mesh_.triangles[t];
      const Eigen::Vector3f p = closestPointOnTriangle(
          q, mesh_.vertices[tri[0]], mesh_.vertices[tri[1]], mesh_.vertices[tri[2]]);
      best = std::min(best, static_cast<double>((p - q).norm()));
    }
  });
  return best <= cell_m_ ? best : kInfinity;
}

Eigen::Vector3f closestPointOnTriangle(const Eigen::Vector3f& p, const Eigen::Vector3f& a,
                                       const Eigen::Vector3f& b, const Eigen::Vector3f& c) {
  const Eigen::Vector3f ab = b - a, ac = c - a, ap = p - a;
  const float d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0f && d2 <= 0.0f) return a;  // vertex region a
  const Eigen::Vector3f bp = p - b;
  const float d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0f && d4 <= d3) return b;
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return a + ab * (d1 / (d1 - d3));  // edge ab
  const Eigen::Vector3f cp = p - c;
  const float d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0f && d5 <= d6) return c;
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return a + ac * (d2 / (d2 - d6));  // edge ac
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));  // edge bc
  }
  const float denom = va + vb + vc;
  if (!(std::abs(denom) > 0.0f)) return a;  // degenerate triangle
  const float v = vb / denom, w = vc / denom;
  return a + ab * v + ac * w;  // inside the face
}

}  // namespace strata::eval
