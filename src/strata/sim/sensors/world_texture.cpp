#include "strata/sim/sensors/world_texture.h"

#include <cmath>

#include "strata/core/error.h"
#include "strata/sim/rng.h"

namespace strata::sim {
namespace {

// Lattice offset in cells, irrational fractions so that walls at round coordinates never sit on a
// cell boundary (where rounding would make the pattern flicker).
const Eigen::Vector3d kLatticeOffset(0.3819660112501051, 0.6180339887498949, 0.2928932188134524);

// Uniform value in [0, 1) of the lattice cell containing p.
double cellValue(const Eigen::Vector3d& p_W, double cell_m, std::uint64_t seed) {
  const Eigen::Vector3d q = p_W / cell_m + kLatticeOffset;
  const auto ix = static_cast<std::int64_t>(std::floor(q.x()));
  const auto iy = static_cast<std::int64_t>(std::floor(q.y()));
  const auto iz = static_cast<std::int64_t>(std::floor(q.z()));
  const std::uint64_t h =
      hashCombine(hashCombine(seed, static_cast<std::uint64_t>(ix)), static_cast<std::uint64_t>(iy),
                  static_cast<std::uint64_t>(iz));
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

}  // namespace

void WorldTextureConfig::validate() const {
  if (!(coarse_cell_m > 0.0) || !(fine_cell_m > 0.0)) {
    throw InputError("WorldTextureConfig: coarse_cell_m and fine_cell_m must be positive");
  }
  if (!(fine_weight >= 0.0 && fine_weight <= 1.0)) {
    throw InputError("WorldTextureConfig: fine_weight must lie in [0, 1]");
  }
  if (!(contrast >= 0.0 && contrast <= 1.0)) {
    throw InputError("WorldTextureConfig: contrast must lie in [0, 1]");
  }
}

double worldTexture(const WorldTextureConfig& config, const Eigen::Vector3d& p_W) {
  const double coarse = cellValue(p_W, config.coarse_cell_m, config.seed);
  const double fine = cellValue(p_W, config.fine_cell_m, hash64(config.seed));
  const double value = (1.0 - config.fine_weight) * coarse + config.fine_weight * fine;
  return 1.0 - config.contrast * value;
}

}  // namespace strata::sim
