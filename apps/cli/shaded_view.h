#pragma once
// Pictures of the map for people: shaded renderings of raycast images.
#include "strata/core/types.h"
#include "strata/raycast/raycast.h"

namespace strata::apps {

/// Lambert shading of the raycast normals with a light at the camera, tinted by voxel colour;
/// misses are dark blue so holes stand out.
ColorImage shadedView(const RaycastImage& image, const Eigen::Isometry3d& T_W_C);

}  // namespace strata::apps
