#pragma once
// What the exploration loop scores against the simulator's truth: the free space reachable from
// the start (the volume to explore), the share of it the map has observed, and the true
// clearance of the flown path. Built once per world and start; shared by the runs compared.
// Thread safety: const methods are thread safe.
#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "strata/map/tsdf_map.h"
#include "strata/sim/world/world.h"

namespace strata::explore {

class ExplorationTruth {
 public:
  /// Flood fill of the free voxels (voxel_size_m) inside `bounds_W` from `start_W`.
  /// InputError when the start is outside the bounds or inside a solid.
  ExplorationTruth(const sim::World& world, const Eigen::AlignedBox3f& bounds_W,
                   const Eigen::Vector3f& start_W, float voxel_size_m);
  ~ExplorationTruth();

  /// Share of the reachable free voxels the map observes (weight >= min_weight), in [0, 1].
  double exploredFraction(const TsdfMap& map, float min_weight) const;
  /// Smallest true signed distance to a surface over the positions (metres).
  float minClearance(const std::vector<Eigen::Vector3f>& positions_W) const;
  /// True signed distance at one point (metres, negative inside solids).
  float clearance(const Eigen::Vector3f& p_W) const;
  std::size_t reachableVoxels() const;
  const sim::WorldScene& scene() const { return *scene_; }

 private:
  struct Reachable;
  std::unique_ptr<sim::WorldScene> scene_;
  std::unique_ptr<Reachable> reachable_;
};

}  // namespace strata::explore
