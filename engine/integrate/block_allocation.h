#pragma once
// Kernel 1, block allocation: every block crossed by the truncation band around each valid depth
// sample. Device: shaders/allocate_blocks.comp, dispatched by DeviceFusion. This is the reference.
#include <vector>

#include "core/types.h"
#include "map/camera_math.h"
#include "map/map_config.h"
#include "map/tsdf_map.h"

namespace strata {

/// Blocks crossed by the band [range - truncation, range + truncation] of every valid pixel's ray,
/// sorted (z, y, x) and unique. Same traversal as the shader.
std::vector<BlockIndex> touchedBlocksReference(const DepthImage& depth, const FrameCamera& camera,
                                               const MapConfig& config);

}  // namespace strata
