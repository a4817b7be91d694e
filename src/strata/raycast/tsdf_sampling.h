#pragma once
// Host mirror of shaders/common/tsdf_sample.glsl: voxel lookup and trilinear TSDF sampling.
#include "strata/map/tsdf_map.h"

namespace strata {

/// Voxel at a global index when allocated and observed (weight >= min_weight), else nullptr.
const TsdfVoxel* observedVoxel(const TsdfMap& map, const GlobalVoxelIndex& v, float min_weight);

/// Trilinear TSDF at p_W from the 8 surrounding voxel centres; false when any is unobserved.
bool sampleTsdf(const TsdfMap& map, const Eigen::Vector3f& p_W, float min_weight, float* tsdf_m);

}  // namespace strata
