#pragma once
// Kernel 1, block allocation. Device: shaders/integrate/allocate_blocks.comp, dispatched by
// DeviceFusion; allocatedBlocksReference is its reference. The device works per tile of
// gpu::kAllocationTilePx pixels and allocates the blocks of the tile's frustum slab, a superset of
// the blocks its pixels' truncation bands cross (bandBlocksReference); docs/integrate.md gives
// the argument, test_tsdf_fusion checks it on analytic and real frames.
// Thread safety: pure functions.
#include <vector>

#include "strata/core/types.h"
#include "strata/map/camera_math.h"
#include "strata/map/map_config.h"
#include "strata/map/tsdf_map.h"

namespace strata {

/// Blocks crossed by the band [range - truncation, range + truncation] of every valid pixel's ray
/// (with MapConfig::allocate_free_space, every free_space_pixel_stride-th pixel's ray from the near
/// limit), sorted (z, y, x) and unique: what a per-pixel traversal allocates.
std::vector<BlockIndex> bandBlocksReference(const DepthImage& depth, const FrameCamera& camera,
                                            const MapConfig& config);

/// What allocate_blocks.comp allocates, sorted (z, y, x) and unique: per tile, the blocks of the
/// frustum slab where the tile's depths span at most MapConfig::blockSize(), else per quarter
/// tile, else the quarter's band rays; free-space rays as in bandBlocksReference. Always a
/// superset of bandBlocksReference.
std::vector<BlockIndex> allocatedBlocksReference(const DepthImage& depth, const FrameCamera& camera,
                                                 const MapConfig& config);

/// The depth span below which a tile is allocated as one slab (see allocatedBlocksReference).
float maxSlabDepth(const MapConfig& config);

}  // namespace strata
