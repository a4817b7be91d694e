#pragma once
// Label layers of multi-session change detection: per-voxel labels on the host, keyed
// like the TSDF map's blocks. The device stores one uint32 per voxel with the same values
// (shaders/common/change_layout.glsl).
#include <array>
#include <cstdint>
#include <unordered_map>

#include "strata/map/block_index.h"

namespace strata::change {

/// Per-voxel label of the label grid D and of a session's dynamic part.
enum class VoxelLabel : std::uint8_t {
  kUnknown = 0,  // not observed in the layers compared (see each label's rule, change_rules.h)
  kStatic = 1,
  kDynamic = 2,
};

using LabelBlock = std::array<VoxelLabel, kVoxelsPerBlock>;

/// Host copy of a label layer (same block index as the TSDF layers).
struct LabelMap {
  float voxel_size_m = 0.02f;
  std::unordered_map<BlockIndex, LabelBlock, BlockIndexHash> blocks;

  VoxelLabel label(const GlobalVoxelIndex& v) const;  // kUnknown outside allocated blocks
  /// The block, allocated with every voxel kUnknown when absent.
  LabelBlock& allocateBlock(const BlockIndex& b);
  /// Voxels carrying `label` over all blocks.
  std::uint64_t count(VoxelLabel label) const;
};

/// Share of voxels on which two label maps agree, over the union of their blocks, counting only
/// voxels where at least one of them is not kUnknown (a missing block reads kUnknown). 1 when
/// neither has such a voxel.
double labelAgreement(const LabelMap& a, const LabelMap& b);

}  // namespace strata::change
