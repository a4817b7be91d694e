#pragma once
// Edge-preserving smoothing of the live depth before tracking (KinectFusion's bilateral filter).
#include "strata/core/types.h"
#include "strata/map/map_config.h"

namespace strata {

/// Bilateral filter: each valid pixel becomes the weighted mean of the valid depths within
/// ceil(2 sigma_px) pixels, weights exp(-|du|² / 2 sigma_px²) · exp(-(d' - d)² / 2 (sigma_share
/// d)²), the range sigma a share of the pixel's own depth d (sensor noise grows with depth).
/// Invalid pixels (0, or outside [map.min_depth_m, map.max_depth_m]) stay 0 and never contribute.
/// sigma_px = 0 returns the depth with invalid pixels zeroed.
DepthImage bilateralFilterDepth(const DepthImage& depth, const MapConfig& map, float sigma_px,
                                float sigma_share);

}  // namespace strata
