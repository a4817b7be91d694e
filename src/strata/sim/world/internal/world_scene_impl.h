#pragma once
// WorldScene's state (internal: shared by world_scene.cpp and world_scene_distance.cpp).
#include <Eigen/Geometry>
#include <vector>

#include "strata/sim/world/internal/scene_assets.h"
#include "strata/sim/world/world_scene.h"

namespace strata::sim {

struct WorldScene::Impl {
  std::shared_ptr<const SceneAssets> assets;
  RtcScenePtr top;  // instance id = object id; 0 is the static scene
  /// Object frame to world by object id (0: identity), double for distances, float for normals.
  std::vector<Eigen::Isometry3d> T_W_O;
  std::vector<Eigen::Matrix3f> R_W_O;
  int session = 0;
  int threads = 2;
  int chunk_rays = 1024;

  /// Inside any closed part: majority of three crossing-parity votes. Also returns the nearest
  /// crossing distance seen (an upper bound of the distance to the surface; +inf when none).
  bool inside(const Eigen::Vector3f& p_W, float* nearest_hit_m) const;
  /// Distance to the nearest triangle, searching within radius_m (+inf: everywhere).
  double nearestDistance(const Eigen::Vector3d& p_W, float radius_m) const;
};

}  // namespace strata::sim
