#pragma once
// The live frame's image pyramid for coarse-to-fine tracking (host): depth by block averaging,
// then a vertex and a normal map per level in the camera frame.
#include <vector>

#include "strata/core/types.h"
#include "strata/map/map_config.h"

namespace strata {

/// One level: its intrinsics and, per pixel, xyz + w (w = 1 valid, 0 invalid).
struct LiveLevel {
  CameraIntrinsics intrinsics;
  DepthImage depth;
  std::vector<Eigen::Vector4f> vertex_C;  // depth * ray, camera frame, metres
  std::vector<Eigen::Vector4f> normal_C;  // unit, facing the camera (estimateNormalsReference)
  std::uint32_t valid = 0;                // pixels with both a vertex and a normal
};

/// Intrinsics of the level below (half the size; pixel centres at integer coordinates, so
/// c' = (c + 0.5) / 2 - 0.5).
CameraIntrinsics halfIntrinsics(const CameraIntrinsics& intrinsics);

/// Half-resolution depth: each pixel the mean of the valid depths of its 2x2 block that lie
/// within threshold_m of the block's nearest valid depth; 0 when the block has none. Depth
/// outside [map.min_depth_m, map.max_depth_m] is invalid.
DepthImage halfDepth(const DepthImage& depth, const MapConfig& map, float threshold_m);

/// `levels` levels, 0 the input. Normals follow map.normal_max_relative_jump at discontinuities.
std::vector<LiveLevel> buildLivePyramid(const DepthImage& depth, const CameraIntrinsics& intrinsics,
                                        const MapConfig& map, int levels, float threshold_m);

}  // namespace strata
