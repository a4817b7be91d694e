#pragma once
// Analytic scenes for the planning tests: a signed distance function (boxes and spheres) written
// into every voxel of a range of blocks as an observed TSDF, and its ESDF by the host reference
// (computeEsdfReference). The same TSDF uploads to the device for DeviceEsdf. Exact distances come
// from the SDF itself, so tests can hold planners and checks to the true geometry.
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "strata/map/esdf_layer.h"
#include "strata/map/tsdf_map.h"

namespace strata::test {

/// Signed distance to the obstacles (metres, negative inside).
using Sdf = std::function<float(const Eigen::Vector3f&)>;

struct Box {
  Eigen::Vector3f lo, hi;
};
struct Ball {
  Eigen::Vector3f centre;
  float radius_m;
};

/// Exact signed distance to an axis-aligned box.
float boxDistance(const Eigen::Vector3f& p, const Box& box);
/// Minimum over the boxes and balls (+inf without any).
float sceneDistance(const Eigen::Vector3f& p, const std::vector<Box>& boxes,
                    const std::vector<Ball>& balls);
/// Smallest SDF value along the segment, sampled every millimetre.
float segmentDistance(const Sdf& sdf, const Eigen::Vector3f& a, const Eigen::Vector3f& b);

struct AnalyticMap {
  TsdfMap tsdf{MapConfig{}};
  EsdfMap esdf;  // computeEsdfReference(tsdf)
};

/// Blocks block_lo..block_hi (inclusive, every axis) all observed with tsdf = clamp(sdf).
AnalyticMap makeAnalyticMap(const Sdf& sdf, const Eigen::Vector3i& block_lo,
                            const Eigen::Vector3i& block_hi, float voxel_size_m,
                            float max_distance_m);

/// The room of the planner tests: x in [-3.2, 3.2), y in [-2.4, 2.4), z in [0, 1.6) (voxel
/// 0.1 m; beyond it nothing is allocated), split at x = 0 by a wall 0.2 m thick with a door at
/// y in [kDoorLoY, kDoorHiY] over the full height, or without a door.
struct RoomScene {
  static constexpr float kVoxelSizeM = 0.1f;
  static constexpr float kDoorLoY = 0.4f;
  static constexpr float kDoorHiY = 1.6f;
  static constexpr float kWallHalfX = 0.1f;
  std::vector<Box> walls;
  AnalyticMap map;
  float distance(const Eigen::Vector3f& p) const { return sceneDistance(p, walls, {}); }
};
const RoomScene& roomScene(bool door_open);

}  // namespace strata::test
