#pragma once
// One session of a world as an Embree ray scene: the shared static scene and one instance per
// present object (World::buildScene makes these; building one is cheap because the static and
// per-object scenes are shared between sessions).
//
// intersect(): packets of 16 rays (rtcIntersect16) over std::thread workers; each hit reports t,
// the unit geometric normal facing the ray, the object id (0 = static world, 1.. = objects) and the
// material.
// signedDistance(): |d| is the exact distance to the nearest triangle (rtcPointQuery with our own
// point-triangle distance in double precision); the sign says whether the point is inside a solid.
// occupied(): inside a solid = inside any closed part (a wall, a chair leg, ...). For each of three
// fixed, irregular ray directions the crossings are counted per part; odd = inside that part. The
// three answers vote (majority), so a ray grazing an edge or a hole in a non-closed mesh file
// rarely flips the result. NOTE: inside overlapping or touching solids (a box on the floor, rooms
// sharing a wall) the nearest triangle can be an internal contact face, so |d| there can be less
// than the depth below the union's surface; outside every solid it is exact.
#include <memory>

#include "strata/sim/ray_scene.h"

namespace strata::sim {

struct SceneAssets;
struct SessionTruth;

class WorldScene : public RayScene {
 public:
  struct Config {
    /// Worker threads for intersect(); 0: the hardware's count (at least 2).
    int threads = 0;
    /// Rays a worker claims at once: large enough to amortise the claim, a multiple of 16.
    int chunk_rays = 1024;
  };

  /// Used by World::buildScene. Error naming the Embree call on failure.
  WorldScene(std::shared_ptr<const SceneAssets> assets, const SessionTruth& session,
             const Config& config);
  ~WorldScene() override;
  WorldScene(const WorldScene&) = delete;
  WorldScene& operator=(const WorldScene&) = delete;

  /// Thread safe. Rays with a non-finite origin or direction report no hit.
  void intersect(const std::vector<Ray>& rays, std::vector<RayHit>& hits) const override;
  /// Thread safe. Metres, negative inside.
  float signedDistance(const Eigen::Vector3f& p_W) const override;
  /// Thread safe. Cheaper than signedDistance (no closest-point search).
  bool occupied(const Eigen::Vector3f& p_W) const override;

  /// Thread safe. Unsigned distance to the nearest triangle, double precision.
  double distanceToSurface(const Eigen::Vector3d& p_W) const;

  int sessionIndex() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace strata::sim
