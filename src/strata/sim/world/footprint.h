#pragma once
// Object footprints on the floor (oriented rectangles) and the tests that placement needs.
#include <Eigen/Core>

#include "strata/sim/world/world_spec.h"

namespace strata::sim {

struct Footprint {
  Eigen::Vector2d centre_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d half_m = Eigen::Vector2d::Zero();  // half extents along the rotated x, y axes
  double yaw_rad = 0.0;
};

Footprint makeFootprint(const Eigen::Vector2d& half_m, const Eigen::Vector2d& at_m, double yaw_deg);

/// True when `a` grown by clearance_m on every side intersects `b` (separating-axis test).
/// NOTE: the grown rectangle keeps square corners, so the clearance is slightly conservative there.
bool overlaps(const Footprint& a, const Footprint& b, double clearance_m);

/// True when all four corners of `f` lie in the region.
bool inside(const Footprint& f, const RegionSpec& region);

}  // namespace strata::sim
