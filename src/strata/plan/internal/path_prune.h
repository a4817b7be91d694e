#pragma once
// Line-of-sight pruning of a polyline: from each kept point, skip ahead to the farthest later
// point whose straight segment is free (CollisionChecker::segmentFree, the capsule test), so a
// grid path loses its staircase. The first and last points are always kept; a path whose own
// segments are free stays free.
// Thread safety: as the checker (not thread safe).
#include <Eigen/Core>
#include <vector>

#include "strata/plan/collision_checker.h"

namespace strata::plan {

std::vector<Eigen::Vector3f> prunePath(const std::vector<Eigen::Vector3f>& path_W,
                                       CollisionChecker& checker, float radius_m,
                                       UnknownPolicy unknown);

}  // namespace strata::plan

namespace strata::plan {

/// Pulls a pruned path taut: each interior point is moved towards the midpoint of its neighbours
/// (half, a quarter, an eighth of the way, the first whose two segments stay free), for `sweeps`
/// passes. Points leave the voxel centres; every segment of the result passed segmentFree.
std::vector<Eigen::Vector3f> relaxPath(std::vector<Eigen::Vector3f> path_W,
                                       CollisionChecker& checker, float radius_m,
                                       UnknownPolicy unknown, int sweeps = 4);

}  // namespace strata::plan
