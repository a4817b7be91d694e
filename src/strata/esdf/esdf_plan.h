#pragma once
// Host-side planning of an ESDF update (internal to DeviceEsdf): which blocks are recomputed, which
// blocks supply their sites, and how the dense working box is cut when it does not fit in memory.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "strata/map/block_index.h"

namespace strata {

/// An axis-aligned box of blocks, bounds inclusive. Empty when any min > max.
struct BlockBox {
  Eigen::Vector3i min = Eigen::Vector3i::Constant(1);
  Eigen::Vector3i max = Eigen::Vector3i::Zero();

  bool empty() const { return (min.array() > max.array()).any(); }
  bool contains(const BlockIndex& b) const {
    return (b.array() >= min.array()).all() && (b.array() <= max.array()).all();
  }
  void include(const BlockIndex& b);
  BlockBox dilated(int blocks) const;
  BlockBox intersected(const BlockBox& other) const;
  Eigen::Vector3i sizeBlocks() const {
    return empty() ? Eigen::Vector3i::Zero() : Eigen::Vector3i(max - min + Eigen::Vector3i::Ones());
  }
  std::uint64_t voxelCount() const;
};

/// One block listed for a kernel: its coordinates relative to the working box (in blocks) and its
/// pool slot. Mirrors the ivec4 lists of esdf_gather_sites.comp and esdf_scatter.comp.
struct ListedBlock {
  std::int32_t x, y, z;
  std::uint32_t slot;
};
static_assert(sizeof(ListedBlock) == 16, "ListedBlock is an ivec4 in the shaders");

/// One dense pass: the working box is `sites` (every voxel of it takes part in the transform);
/// only the blocks of `update` are written back.
struct EsdfJob {
  BlockBox update;
  BlockBox sites;
  std::vector<ListedBlock> gather;   // allocated blocks inside `sites`
  std::vector<ListedBlock> scatter;  // allocated blocks inside `update`
};

/// Jobs that recompute every allocated block inside `update`. Sites come from `update` dilated by
/// `reach_blocks`, clipped to `map_box`. When that box has more than `max_box_voxels` voxels, the
/// update box is cut along its longest axis into slabs (each with its own dilated site box, so
/// each slab is still exact). Throws DeviceError naming the box when even one block-thick slab is
/// too large. `slot_blocks[s]` is the block of pool slot s.
std::vector<EsdfJob> planEsdfJobs(const BlockBox& update, const BlockBox& map_box, int reach_blocks,
                                  const std::vector<BlockIndex>& slot_blocks,
                                  std::uint64_t max_box_voxels);

}  // namespace strata
