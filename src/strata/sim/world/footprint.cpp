#include "strata/sim/world/footprint.h"

#include <array>
#include <cmath>
#include "strata/core/math_constants.h"

namespace strata::sim {
namespace {

std::array<Eigen::Vector2d, 2> axes(const Footprint& f) {
  const double c = std::cos(f.yaw_rad), s = std::sin(f.yaw_rad);
  return {Eigen::Vector2d(c, s), Eigen::Vector2d(-s, c)};
}

/// Half the length of f's projection onto the unit axis.
double projectedRadius(const Footprint& f, const Eigen::Vector2d& axis) {
  const auto [u, v] = axes(f);
  return f.half_m.x() * std::abs(u.dot(axis)) + f.half_m.y() * std::abs(v.dot(axis));
}

}  // namespace

Footprint makeFootprint(const Eigen::Vector2d& half_m, const Eigen::Vector2d& at_m,
                        double yaw_deg) {
  return {at_m, half_m, yaw_deg * kPi / 180.0};
}

bool overlaps(const Footprint& a, const Footprint& b, double clearance_m) {
  Footprint grown = a;
  grown.half_m += Eigen::Vector2d::Constant(clearance_m);
  const Eigen::Vector2d d = b.centre_m - a.centre_m;
  const auto a_axes = axes(grown);
  const auto b_axes = axes(b);
  for (const Eigen::Vector2d& axis : {a_axes[0], a_axes[1], b_axes[0], b_axes[1]}) {
    // Touching (equal) counts as overlapping so that clearance 0 still keeps solids apart.
    if (std::abs(d.dot(axis)) > projectedRadius(grown, axis) + projectedRadius(b, axis)) {
      return false;
    }
  }
  return true;
}

bool inside(const Footprint& f, const RegionSpec& region) {
  const auto [u, v] = axes(f);
  for (const double su : {-1.0, 1.0}) {
    for (const double sv : {-1.0, 1.0}) {
      const Eigen::Vector2d corner = f.centre_m + su * f.half_m.x() * u + sv * f.half_m.y() * v;
      if ((corner.array() < region.min_m.array()).any() ||
          (corner.array() > region.max_m.array()).any()) {
        return false;
      }
    }
  }
  return true;
}

}  // namespace strata::sim
