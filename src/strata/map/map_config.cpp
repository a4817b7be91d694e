#include "strata/map/map_config.h"

#include <cmath>
#include <sstream>

#include "strata/core/error.h"
#include "strata/core/validate.h"
#include "strata/map/block_index.h"

namespace strata {

float MapConfig::blockSize() const { return voxel_size_m * static_cast<float>(kBlockEdge); }

void MapConfig::validate() const {
  requirePositive(voxel_size_m, "MapConfig", "voxel_size_m");
  requirePositive(truncation_voxels, "MapConfig", "truncation_voxels");
  requirePositive(max_weight, "MapConfig", "max_weight");
  requirePositive(max_depth_m, "MapConfig", "max_depth_m");
  if (!std::isfinite(min_depth_m) || min_depth_m < 0.0f || min_depth_m >= max_depth_m) {
    std::ostringstream msg;
    msg << "invalid map config: depth range [" << min_depth_m << ", " << max_depth_m
        << "] m must satisfy 0 <= min < max";
    throw InputError(msg.str());
  }
  if (voxel_size_m < 0.001f || voxel_size_m > 1.0f) {
    std::ostringstream msg;
    msg << "invalid map config: voxel_size_m = " << voxel_size_m << " is outside [0.001, 1] m";
    throw InputError(msg.str());
  }
  if (truncation_voxels < 1.0f) {
    throw InputError("invalid map config: truncation_voxels must be at least 1 voxel");
  }
  if (!std::isfinite(dropoff_start_voxels) || dropoff_start_voxels < 0.0f ||
      dropoff_start_voxels >= truncation_voxels) {
    throw InputError("invalid map config: dropoff_start_voxels must be in [0, truncation_voxels)");
  }
  if (weight_mode != WeightMode::kConstant && weight_mode != WeightMode::kInverseDepthSquared) {
    throw InputError("invalid map config: unknown weight_mode");
  }
  if (distance_mode != DistanceMode::kAlongRay && distance_mode != DistanceMode::kPointToPlane) {
    throw InputError("invalid map config: unknown distance_mode");
  }
  requirePositive(normal_max_relative_jump, "MapConfig", "normal_max_relative_jump");
  if (allocate_free_space && free_space_pixel_stride == 0) {
    throw InputError("invalid map config: free_space_pixel_stride must be positive");
  }
  if (initial_block_capacity == 0) {
    throw InputError("invalid map config: initial_block_capacity must be positive");
  }
  if (initial_hash_capacity < 64 || (initial_hash_capacity & (initial_hash_capacity - 1)) != 0) {
    throw InputError("invalid map config: initial_hash_capacity must be a power of two >= 64");
  }
}

std::string MapConfig::describe() const {
  std::ostringstream out;
  out << "voxel " << voxel_size_m * 100.0f << " cm, truncation " << truncationDistance() * 100.0f
      << " cm, max weight " << max_weight << ", depth [" << min_depth_m << ", " << max_depth_m
      << "] m, weight "
      << (weight_mode == WeightMode::kConstant ? "constant" : "1/z^2")
      << (weight_dropoff ? " with drop-off" : "") << ", distance "
      << (distance_mode == DistanceMode::kPointToPlane ? "point-to-plane" : "along the ray")
      << (allocate_free_space ? ", free space allocated" : "");
  return out.str();
}

}  // namespace strata
