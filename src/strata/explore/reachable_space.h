#pragma once
// Ground truth for exploration on a simulated world: the free space a robot could reach from its
// start (what "fully explored" means), how much of it a map has observed, and how close a flown
// path came to any surface.
//
// Reachable space: the voxel grid over `bounds_W` (voxel (0,0,0) at the box's min corner, as many
// voxels per axis as cover the box) whose centres lie in free space — outside every solid and
// more than half a voxel from any surface (true geometry) — and are 6-connected through such
// voxels to the start's voxel. Method: the free test runs on cells of voxels first; a cell whose
// centre is farther from every surface than its half-diagonal plus half a voxel is all free or all
// inside (one occupancy test), the others split in eight down to single voxels, so exact distance
// queries run only near surfaces; cells go to worker threads. Then a flood fill from the start.
// Errors: InputError for a non-positive voxel size, an empty box, a start outside the box or not
// in free space, or a grid over 2^31 voxels.
// Thread safety: all functions are thread safe (they only read the scene and the map).
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "strata/map/tsdf_map.h"
#include "strata/sim/world/world_scene.h"

namespace strata::explore {

struct ReachableSpace {
  Eigen::Vector3d origin_W = Eigen::Vector3d::Zero();  // min corner of voxel (0, 0, 0)
  double voxel_size_m = 0.0;
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();
  std::vector<std::uint8_t> reachable;  // 1 = reachable; voxel (x, y, z) at x + nx (y + ny z)
  std::size_t reachable_count = 0;
  std::size_t free_count = 0;  // free voxels, reachable or not
  double volume_m3 = 0.0;      // reachable_count x voxel volume

  Eigen::Vector3d center(int x, int y, int z) const {
    return origin_W + (Eigen::Vector3d(x, y, z).array() + 0.5).matrix() * voxel_size_m;
  }
  bool isReachable(int x, int y, int z) const {
    return reachable[static_cast<std::size_t>(x) +
                     static_cast<std::size_t>(dims.x()) *
                         (static_cast<std::size_t>(y) + static_cast<std::size_t>(dims.y()) * z)] !=
           0;
  }
};

ReachableSpace computeReachableSpace(const sim::WorldScene& scene,
                                     const Eigen::AlignedBox3d& bounds_W,
                                     const Eigen::Vector3d& start_W, double voxel_size_m);

/// Share of the reachable voxels whose centre lies in a voxel of `map` observed with weight >=
/// min_weight (the map's voxel size may differ from the grid's). 0 when nothing is reachable.
double exploredFraction(const ReachableSpace& space, const TsdfMap& map, float min_weight);

/// The smallest true distance from any of `positions_W` to any surface (metres; +infinity for no
/// positions). A path is collision-free for a robot of radius r when this exceeds r.
double minClearanceAlong(const sim::WorldScene& scene,
                         const std::vector<Eigen::Vector3d>& positions_W);

}  // namespace strata::explore
