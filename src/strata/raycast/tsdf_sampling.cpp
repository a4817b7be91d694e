#include "strata/raycast/tsdf_sampling.h"

#include <cmath>

namespace strata {

const TsdfVoxel* observedVoxel(const TsdfMap& map, const GlobalVoxelIndex& v, float min_weight) {
  const TsdfVoxel* voxel = map.findVoxel(v);
  return (voxel != nullptr && voxel->weight >= min_weight) ? voxel : nullptr;
}

bool sampleTsdf(const TsdfMap& map, const Eigen::Vector3f& p_W, float min_weight, float* tsdf_m) {
  const float voxel_size_m = map.config().voxel_size_m;
  const Eigen::Vector3f g = p_W / voxel_size_m - Eigen::Vector3f::Constant(0.5f);
  const Eigen::Vector3f base_f = g.array().floor();
  const Eigen::Vector3i base = base_f.cast<int>();
  const Eigen::Vector3f f = g - base_f;
  float values[8];
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3i corner = base + Eigen::Vector3i(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    const TsdfVoxel* voxel = observedVoxel(map, corner, min_weight);
    if (voxel == nullptr) return false;
    values[i] = voxel->tsdf_m;
  }
  auto mix = [](float a, float b, float t) { return a * (1.0f - t) + b * t; };
  const float x00 = mix(values[0], values[1], f.x());
  const float x10 = mix(values[2], values[3], f.x());
  const float x01 = mix(values[4], values[5], f.x());
  const float x11 = mix(values[6], values[7], f.x());
  *tsdf_m = mix(mix(x00, x10, f.y()), mix(x01, x11, f.y()), f.z());
  return true;
}

}  // namespace strata
