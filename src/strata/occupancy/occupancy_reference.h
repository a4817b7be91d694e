#pragma once
// The occupancy update of one depth frame in plain C++: the specification of the device kernels
// (shaders/occupancy_mark.comp + occupancy_update.comp, dispatched by DeviceOccupancy).
#include <cstdint>

#include "strata/core/types.h"
#include "strata/map/camera_math.h"
#include "strata/occupancy/occupancy_map.h"

namespace strata {

/// Kernel inputs of one frame (shared by reference and device so both see the same floats).
OccupancyRayCamera occupancyRayCamera(const FrameCamera& camera, const OccupancyConfig& config,
                                      float voxel_size_m);

struct OccupancyScanCounts {
  std::uint64_t rays = 0;            // valid samples that cast a ray
  std::uint64_t updated_voxels = 0;  // voxels that got their one update of this scan
};

/// Casts a ray from the camera through every pixel_stride-th pixel (both axes): voxels passed
/// through are marked miss, the endpoint's voxel hit (if within max range); then every marked
/// voxel gets one update, hit over miss (occupancyUpdate). Blocks are allocated as needed.
/// `config` must be valid and the depth image must match the camera's size.
OccupancyScanCounts integrateOccupancyReference(const DepthImage& depth, const FrameCamera& camera,
                                                const OccupancyConfig& config, OccupancyMap& map);

}  // namespace strata
