#pragma once
// An analytic ESDF for the query tests: a sphere shell of sites in a cube of blocks, exact
// distances and site offsets by brute force, with an unobserved slab and an unallocated block.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "strata/map/device_tsdf_map.h"
#include "strata/map/esdf_layer.h"
#include "strata/vk/vk.h"

namespace strata::test {

struct SphereEsdfScene {
  static constexpr float kVoxelSizeM = 0.05f;
  static constexpr float kMaxDistanceM = 1.0f;
  static constexpr int kBlockMin = -3;       // blocks kBlockMin..kBlockMax on every axis
  static constexpr int kBlockMax = 2;        // voxels -24..23: x, y, z in [-1.2, 1.2) m
  static constexpr int kUnknownSlabX0 = 14;  // voxels with x index 14, 15 (x in [0.7, 0.8) m)
  static constexpr int kUnknownSlabX1 = 16;  // are allocated but never observed
  inline static const BlockIndex kMissingBlock{2, 2, 2};  // not allocated

  Eigen::Vector3f centre_W{0.02f, -0.03f, 0.01f};
  float radius_m = 0.5f;
  EsdfMap map;
  std::vector<Eigen::Vector3f> sites_W;  // site voxel centres

  /// Exact signed distance to the sphere surface (not to the site centres).
  float surfaceDistance(const Eigen::Vector3f& p_W) const {
    return (p_W - centre_W).norm() - radius_m;
  }
  /// Brute force: distance from p to the nearest site centre.
  float nearestSiteDistance(const Eigen::Vector3f& p_W) const;
};

/// Builds the scene (about 0.2 s: brute-force nearest sites).
const SphereEsdfScene& sphereEsdfScene();

/// The scene's blocks on the device: a TSDF map with the same blocks (for the block hash) and an
/// ESDF pool in the slot order DeviceTsdfMap::upload assigns. Stands in for DeviceEsdf.
struct DeviceSphereEsdf {
  std::unique_ptr<DeviceTsdfMap> tsdf;
  vk::Buffer esdf_pool;
};
DeviceSphereEsdf uploadSphereEsdf(vk::Context& context, const SphereEsdfScene& scene);

}  // namespace strata::test
