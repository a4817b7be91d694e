#pragma once
// Landmark lower bounds for searches on the topological map's portal graph (the ALT heuristic of
// Goldberg and Harrelson, 2005): graph distances from a few landmark portals to every portal; by
// the triangle inequality |d(L, goal) - d(L, n)| <= d(n, goal) for every landmark L, a bound far
// tighter than the straight line where walls force detours. Landmarks are picked farthest-first.
// Thread safety: immutable after construction.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace strata::plan {

struct TopoPortal;

class TopoLandmarks {
 public:
  TopoLandmarks() = default;
  /// `count` landmarks (fewer when the graph has fewer portals) over the graph whose nodes are
  /// `portals` (centres `centres`) and whose edges join the portals of each cluster (CSR lists
  /// `offsets`, `ids`).
  TopoLandmarks(const std::vector<TopoPortal>& portals, const std::vector<Eigen::Vector3f>& centres,
                const std::vector<std::int32_t>& offsets, const std::vector<std::int32_t>& ids,
                int count);

  int count() const { return count_; }
  /// Graph distance from landmark l to portal p (metres); infinity when not connected.
  float distance(int l, std::int32_t p) const {
    return distance_[static_cast<std::size_t>(l) * portals_ + static_cast<std::size_t>(p)];
  }
  std::size_t memoryBytes() const { return distance_.capacity() * sizeof(float); }

 private:
  int count_ = 0;
  std::size_t portals_ = 0;
  std::vector<float> distance_;  // count x portals
};

/// Dijkstra over the portal graph from `source`: the distance to every portal (infinity where
/// not connected).
std::vector<float> portalDistances(const std::vector<TopoPortal>& portals,
                                   const std::vector<Eigen::Vector3f>& centres,
                                   const std::vector<std::int32_t>& offsets,
                                   const std::vector<std::int32_t>& ids, std::int32_t source);

}  // namespace strata::plan
