#pragma once
// Descriptors of a surface cloud shared by observations and models (internal to strata::objects).
#include <Eigen/Core>

#include "strata/objects/object_observation.h"

namespace strata::objects {

/// Edges of the axis-aligned bounding box of the points, sorted descending; zero when empty.
Eigen::Vector3f boundingExtent(const SurfaceCloud& cloud);

/// Mean of the sample colours (0..255 per channel); zero when the cloud has no colours.
Eigen::Vector3f meanColor(const SurfaceCloud& cloud);

}  // namespace strata::objects
