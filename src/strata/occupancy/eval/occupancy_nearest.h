#pragma once
// Nearest-neighbour queries within a radius, for the occupancy / TSDF comparison: uniform hash
// grids over points (occupied voxel centres) and over triangles (a TSDF mesh).
// Thread safety: const methods may be called from several threads at once.
#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "strata/mesh/mesh.h"

namespace strata::eval {

class PointGrid {
 public:
  /// `radius_m`: the largest query radius (the grid's cell edge).
  PointGrid(std::vector<Eigen::Vector3f> points, float radius_m);
  /// Distance to the nearest point if it is within radius_m, else +infinity.
  double nearestWithin(const Eigen::Vector3f& q) const;

 private:
  std::vector<Eigen::Vector3f> points_;
  float cell_m_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

class TriangleGrid {
 public:
  TriangleGrid(const Mesh& mesh, float radius_m);
  /// Distance to the nearest point on any triangle if within radius_m, else +infinity.
  double nearestWithin(const Eigen::Vector3f& q) const;

 private:
  const Mesh& mesh_;
  float cell_m_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

/// Closest point to `p` on triangle (a, b, c) (Ericson, Real-Time Collision Detection, 5.1.5).
Eigen::Vector3f closestPointOnTriangle(const Eigen::Vector3f& p, const Eigen::Vector3f& a,
                                       const Eigen::Vector3f& b, const Eigen::Vector3f& c);

}  // namespace strata::eval
