#pragma once
// Nearest-surface queries for evaluation: triangles of tagged meshes in a uniform hash grid.
#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "strata/mesh/mesh.h"

namespace strata::change {

/// Thread safety: const methods may run concurrently once building is done.
class SurfaceIndex {
 public:
  /// Queries reach at most `max_query_m` (the grid's cell edge): enough for "within tolerance".
  explicit SurfaceIndex(float max_query_m);

  /// Adds the triangles of `mesh` (world frame) under `tag` (e.g. an object id).
  void add(const Mesh& mesh, int tag = 0);

  struct Hit {
    float distance_m = 0.0f;
    int tag = 0;
  };
  /// The nearest triangle within max_m (<= max_query_m); false when there is none.
  bool nearest(const Eigen::Vector3f& p, float max_m, Hit& hit) const;
  bool within(const Eigen::Vector3f& p, float max_m) const {
    Hit hit;
    return nearest(p, max_m, hit);
  }
  bool empty() const { return triangles_.empty(); }

 private:
  struct Triangle {
    Eigen::Vector3d a, b, c;
    int tag;
  };
  std::uint64_t cellKey(const Eigen::Vector3i& cell) const;
  Eigen::Vector3i cellOf(const Eigen::Vector3f& p) const;

  float cell_m_;
  std::vector<Triangle> triangles_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

/// Share of `points` within `distance_m` of `surface` (0 for no points).
double shareWithin(const std::vector<Eigen::Vector3f>& points, const SurfaceIndex& surface,
                   float distance_m);

}  // namespace strata::change
