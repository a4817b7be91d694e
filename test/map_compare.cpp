#include "map_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace strata::test {
namespace {

bool colorsClose(std::uint32_t a, std::uint32_t b) {
  for (int c = 0; c < 3; ++c) {
    const int ca = static_cast<int>((a >> (8 * c)) & 255u);
    const int cb = static_cast<int>((b >> (8 * c)) & 255u);
    if (std::abs(ca - cb) > 1) return false;
  }
  return true;
}

}  // namespace

MapDifference compareMaps(const TsdfMap& a, const TsdfMap& b, float distance_tolerance_m,
                          float weight_tolerance) {
  MapDifference diff;
  for (const auto& [index, block_b] : b.blocks()) {
    if (a.findBlock(index) == nullptr) ++diff.blocks_only_in_b;
  }
  for (const auto& [index, block_a] : a.blocks()) {
    const TsdfBlock* block_b = b.findBlock(index);
    if (block_b == nullptr) {
      ++diff.blocks_only_in_a;
      continue;
    }
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      const TsdfVoxel& va = block_a[i];
      const TsdfVoxel& vb = (*block_b)[i];
      if (va.weight <= 0.0f && vb.weight <= 0.0f) continue;
      ++diff.updated_voxels;
      const double d = std::abs(double(va.tsdf_m) - double(vb.tsdf_m));
      diff.max_distance_difference_m = std::max(diff.max_distance_difference_m, d);
      if (d > distance_tolerance_m) ++diff.distance_mismatches;
      // Relative to the weight, or to one unit observation for lighter voxels: drop-off weights
      // near the end of the band are tiny and their relative rounding is meaningless.
      const float scale = std::max({std::abs(va.weight), std::abs(vb.weight), 1.0f});
      if (std::abs(va.weight - vb.weight) > weight_tolerance * scale) ++diff.weight_mismatches;
      if (!colorsClose(va.color_rgba, vb.color_rgba)) ++diff.color_mismatches;
    }
  }
  return diff;
}

}  // namespace strata::test
