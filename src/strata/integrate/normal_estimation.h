#pragma once
// Per-pixel depth normals for the point-to-plane distance. Device: shaders/estimate_normals.comp.
#include <vector>

#include "strata/core/types.h"
#include "strata/map/camera_math.h"
#include "strata/map/map_config.h"

namespace strata {

/// Reference of estimate_normals.comp: xyz unit normal in the camera frame facing the camera,
/// w = 1 where valid, all zero at borders, invalid neighbours and depth discontinuities.
std::vector<Eigen::Vector4f> estimateNormalsReference(const DepthImage& depth,
                                                      const FrameCamera& camera,
                                                      const MapConfig& config);

}  // namespace strata
