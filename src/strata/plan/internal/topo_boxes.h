#pragma once
// The clusters of the topological map (topo_map.h): greedy axis-aligned boxes over a mask of
// available voxels (traversable and unclaimed), grown from seeds in a given order.
// Thread safety: pure functions.
#include <cstdint>
#include <vector>

#include "strata/map/esdf_layer.h"
#include "strata/plan/traversability.h"

namespace strata::plan {

/// Boxes covering every available cell of `region` exactly once (cells x fastest). Each seed
/// (a cell index, in the order given) still available starts a box that grows in turn along
/// +x, -x, +y, -y, +z, -z by one layer while the whole layer is available; a direction that
/// fails once stays closed (the layer only grows). Clears `available` where boxes claim.
std::vector<VoxelBox> growBoxes(const VoxelBox& region, std::vector<std::uint8_t>& available,
                                const std::vector<std::int64_t>& seeds);

/// The available cells of `region` ordered by decreasing ESDF distance at their voxel (unknown
/// voxels count as 0), ties by index: the seed order of growBoxes.
std::vector<std::int64_t> seedsByClearance(const EsdfMap& esdf, const VoxelBox& region,
                                           const std::vector<std::uint8_t>& available);

}  // namespace strata::plan
