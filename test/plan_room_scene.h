#pragma once
// An analytic scene for the planner tests: a closed room (interior x in [0, 4], y in [0, 3],
// z in [0, 1.2] m) split by a wall at x in [1.9, 2.1] with a full-height door at y in
// [1.9, 2.7] (or closed), as a fully observed TSDF of the exact signed distance (10 cm voxels)
// and its exact ESDF (computeEsdfReference, max distance 1 m).
#include <Eigen/Geometry>

#include "strata/map/esdf_layer.h"
#include "strata/map/tsdf_map.h"

namespace strata::test {

struct PlanRoom {
  static constexpr float kVoxelM = 0.1f;
  static constexpr float kMaxDistanceM = 1.0f;
  static constexpr double kWallX0 = 1.9, kWallX1 = 2.1;  // the dividing wall
  static constexpr double kDoorY0 = 1.9, kDoorY1 = 2.7;  // its door
  bool door_open = true;
  /// An extra obstacle (a box) when not empty.
  Eigen::AlignedBox3d extra;

  /// Exact signed distance to the scene's surfaces (metres, negative inside solids).
  double signedDistance(const Eigen::Vector3d& p) const;
  TsdfMap tsdf() const;
  EsdfMap esdf() const;
};

}  // namespace strata::test
