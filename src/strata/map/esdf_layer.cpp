#include "strata/map/esdf_layer.h"

#include <cmath>
#include <sstream>

#include "strata/core/error.h"

namespace strata {

void EsdfConfig::validate(float voxel_size_m) const {
  std::ostringstream problem;
  if (!std::isfinite(max_distance_m) || max_distance_m <= 0.0f) {
    problem << "max_distance_m = " << max_distance_m << " must be positive";
  } else if (max_distance_m / voxel_size_m > static_cast<float>(kEsdfMaxOffset)) {
    problem << "max_distance_m = " << max_distance_m << " is more than " << kEsdfMaxOffset
            << " voxels of " << voxel_size_m << " m (site offsets are stored in 10 bits)";
  } else if (!std::isfinite(site_threshold_voxels) || site_threshold_voxels <= 0.0f) {
    problem << "site_threshold_voxels = " << site_threshold_voxels << " must be positive";
  } else if (!std::isfinite(min_weight) || min_weight <= 0.0f) {
    problem << "min_weight = " << min_weight << " must be positive";
  } else if (tsdf_layer < 0) {
    problem << "tsdf_layer = " << tsdf_layer << " must be 0 or more";
  }
  if (!problem.str().empty()) throw InputError("invalid ESDF config: " + problem.str());
}

const EsdfVoxel* EsdfMap::findVoxel(const GlobalVoxelIndex& v) const {
  const BlockIndex b = blockOfVoxel(v);
  const auto it = blocks.find(b);
  if (it == blocks.end()) return nullptr;
  const Eigen::Vector3i local = v - b * kBlockEdge;
  return &it->second[linearVoxelIndex(local.x(), local.y(), local.z())];
}

}  // namespace strata
