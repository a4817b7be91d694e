#pragma once
// A procedural, world-anchored grey texture: piecewise-constant values on two cubic lattices
// (value noise without interpolation), so every surface shows sharp, non-repeating corners for
// feature trackers, and the same point looks the same from every view and session.
// NOTE: anchored to world coordinates, not to objects: a moved object shows a different pattern.
#include <Eigen/Core>
#include <cstdint>

namespace strata::sim {

struct WorldTextureConfig {
  double coarse_cell_m = 0.08;  // side of the large cells
  double fine_cell_m = 0.023;   // side of the small cells; not a divisor of the coarse side
  double fine_weight = 0.4;     // share of the fine lattice in [0, 1]
  double contrast = 0.6;        // 0 = flat (factor 1), 1 = cells from black to full albedo
  std::uint64_t seed = 0x5EED;  // fixed by default so every session shares the pattern

  /// Throws InputError naming the first bad field.
  void validate() const;
};

/// Reflectance factor in [1 - contrast, 1] at a surface point.
double worldTexture(const WorldTextureConfig& config, const Eigen::Vector3d& p_W);

}  // namespace strata::sim
