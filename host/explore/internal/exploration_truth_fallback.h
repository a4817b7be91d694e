#pragma once
// TEMPORARY stand-in for host/eval/exploration_truth.h (exploration scored against the
// simulator's truth), so the exploration loop runs before that lands. Same function names;
// delete this header and exploration_truth_fallback.cpp once the real one is merged and include
// "eval/exploration_truth.h" in exploration_eval.cpp instead (the only user).
//
// computeReachableSpace: the voxels (grid floor(p / voxel)) inside `bounds` whose centres are
// free (not inside any solid) and 6-connected through such voxels to the voxel of `start`.
// exploredFraction: the share of them whose map voxel (the map voxel holding the centre) is
// observed (weight >= min_weight). minClearanceAlong: the smallest signed distance to the
// scene's surfaces over the positions (negative inside a solid; +infinity for no positions).
// Thread safety: thread safe (the scene's queries are).
#include <Eigen/Geometry>
#include <vector>

#include "map/tsdf_map.h"
#include "sim/world/world_scene.h"

namespace strata::eval {

struct ReachableSpace {
  float voxel_size_m = 0.1f;
  std::vector<Eigen::Vector3i> voxels;  // global voxel indices
};

/// InputError when the start is not finite, outside the bounds, or inside a solid.
ReachableSpace computeReachableSpace(const sim::WorldScene& scene,
                                     const Eigen::AlignedBox3f& bounds_W,
                                     const Eigen::Vector3f& start_W, float voxel_size_m);

double exploredFraction(const ReachableSpace& reachable, const TsdfMap& map, float min_weight);

float minClearanceAlong(const sim::WorldScene& scene,
                        const std::vector<Eigen::Vector3f>& positions_W);

}  // namespace strata::eval
