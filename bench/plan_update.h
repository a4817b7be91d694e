#pragma once
// The topological map's incremental update in `strata-bench plan`: a box obstacle placed in the
// map (its TSDF voxels set to the box's signed distance where nearer), the ESDF recomputed, then
// TopoMap::update on the blocks whose ESDF changed against a full rebuild on the changed map.
#include <Eigen/Geometry>

#include "json.h"
#include "strata/plan/topo_map.h"
#include "plan_world_map.h"

namespace strata::bench {

/// Times and checks (cover and connectivity of the update against the rebuild) as JSON;
/// `ok` false when they disagree.
Json measureTopoUpdate(const WorldMap& map, const Eigen::AlignedBox3d& obstacle,
                       const plan::TopoOptions& options, bool* ok);

}  // namespace strata::bench
