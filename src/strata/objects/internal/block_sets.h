#pragma once
// Voxel addressing within blocks and sets of block indices the object code gathers from boxes (an
// observation's band, a mapped observation's footprint in the model grid), returned in the maps'
// (z, y, x) order so the work over them is deterministic.
#include <Eigen/Core>
#include <algorithm>
#include <tuple>
#include <unordered_set>
#include <vector>

#include "strata/map/block_index.h"

namespace strata::objects {

using BlockSet = std::unordered_set<BlockIndex, BlockIndexHash>;

/// Adds every block index in [lo, hi] (inclusive, per axis).
inline void insertBlocksInBox(const Eigen::Vector3i& lo, const Eigen::Vector3i& hi,
                              BlockSet& blocks) {
  for (int z = lo.z(); z <= hi.z(); ++z) {
    for (int y = lo.y(); y <= hi.y(); ++y) {
      for (int x = lo.x(); x <= hi.x(); ++x) blocks.insert(BlockIndex(x, y, z));
    }
  }
}

/// Global index of voxel `linear` (linearVoxelIndex order) of block `b`.
inline GlobalVoxelIndex voxelOfBlock(const BlockIndex& b, int linear) {
  return b * kBlockEdge + Eigen::Vector3i(linear % kBlockEdge, linear / kBlockEdge % kBlockEdge,
                                          linear / (kBlockEdge * kBlockEdge));
}

inline std::vector<BlockIndex> sortedBlocks(const BlockSet& blocks) {
  std::vector<BlockIndex> sorted(blocks.begin(), blocks.end());
  std::sort(sorted.begin(), sorted.end(), [](const BlockIndex& a, const BlockIndex& b) {
    return std::make_tuple(a.z(), a.y(), a.x()) < std::make_tuple(b.z(), b.y(), b.x());
  });
  return sorted;
}

}  // namespace strata::objects
