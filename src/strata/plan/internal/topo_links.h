#pragma once
// The links of the topological map (topo_map.h): the portals between touching boxes, each
// cluster's portal list (CSR), and a block -> clusters lookup for locating a voxel's cluster.
// Thread safety: pure function.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "strata/plan/topo_map.h"

namespace strata::plan {

struct TopoLinks {
  std::vector<TopoPortal> portals;
  std::vector<std::int32_t> portal_offsets;  // clusters + 1 entries
  std::vector<std::int32_t> portal_ids;
  std::unordered_map<BlockIndex, std::vector<std::int32_t>, BlockIndexHash> block_clusters;
};

/// `boxes` must be disjoint and inside `bounds`. Linear in the cells of `bounds` (a cluster-id
/// grid is filled and each box's upper faces scanned).
TopoLinks linkClusters(const std::vector<VoxelBox>& boxes, const VoxelBox& bounds,
                       float voxel_size_m);

}  // namespace strata::plan
