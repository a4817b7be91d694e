#pragma once
// Voxel-by-voxel comparison of two TSDF maps (device vs reference, reader vs reader).
#include <cstddef>

#include "strata/map/tsdf_map.h"

namespace strata::test {

struct MapDifference {
  std::size_t blocks_only_in_a = 0;
  std::size_t blocks_only_in_b = 0;
  std::size_t updated_voxels = 0;        // observed in a or b
  std::size_t distance_mismatches = 0;   // |tsdf_a - tsdf_b| > distance_tolerance_m
  std::size_t weight_mismatches = 0;     // relative weight difference > weight_tolerance
  std::size_t color_mismatches = 0;      // any channel differs by more than 1
  double max_distance_difference_m = 0.0;

  double distanceMismatchShare() const {
    return updated_voxels == 0 ? 0.0 : double(distance_mismatches) / double(updated_voxels);
  }
  double weightMismatchShare() const {
    return updated_voxels == 0 ? 0.0 : double(weight_mismatches) / double(updated_voxels);
  }
};

MapDifference compareMaps(const TsdfMap& a, const TsdfMap& b, float distance_tolerance_m,
                          float weight_tolerance);

}  // namespace strata::test
