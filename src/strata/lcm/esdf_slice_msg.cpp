#include "strata/lcm/esdf_slice_msg.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>

namespace strata::lcm_io {

esdf_slice_t makeEsdfSlice(const EsdfMap& esdf, float z_m, std::int64_t utime) {
  esdf_slice_t slice{};
  slice.utime = utime;
  slice.resolution_m = esdf.voxel_size_m;
  const int voxel_z = static_cast<int>(std::floor(z_m / esdf.voxel_size_m));
  slice.z_m = (static_cast<float>(voxel_z) + 0.5f) * esdf.voxel_size_m;
  const int block_z = floorDiv(voxel_z, kBlockEdge);
  int min_x = INT_MAX, min_y = INT_MAX, max_x = INT_MIN, max_y = INT_MIN;
  for (const auto& [b, block] : esdf.blocks) {
    if (b.z() != block_z) continue;
    min_x = std::min(min_x, b.x());
    max_x = std::max(max_x, b.x());
    min_y = std::min(min_y, b.y());
    max_y = std::max(max_y, b.y());
  }
  if (min_x > max_x) return slice;  // no block at this height
  slice.width = (max_x - min_x + 1) * kBlockEdge;
  slice.height = (max_y - min_y + 1) * kBlockEdge;
  slice.origin_x_m = (static_cast<float>(min_x * kBlockEdge) + 0.5f) * esdf.voxel_size_m;
  slice.origin_y_m = (static_cast<float>(min_y * kBlockEdge) + 0.5f) * esdf.voxel_size_m;
  const float unknown = std::numeric_limits<float>::quiet_NaN();
  slice.distance_m.assign(slice.height, std::vector<float>(slice.width, unknown));
  slice.state.assign(slice.height, std::vector<std::int8_t>(slice.width, kSliceOutside));
  for (int row = 0; row < slice.height; ++row) {
    for (int col = 0; col < slice.width; ++col) {
      const GlobalVoxelIndex v(min_x * kBlockEdge + col, min_y * kBlockEdge + row, voxel_z);
      const EsdfVoxel* voxel = esdf.findVoxel(v);
      if (voxel == nullptr) continue;
      if (!esdfObserved(*voxel)) {
        slice.state[row][col] = kSliceUnknown;
        continue;
      }
      slice.state[row][col] = kSliceObserved;
      slice.distance_m[row][col] = voxel->distance_m;
    }
  }
  return slice;
}

}  // namespace strata::lcm_io
