#pragma once
// Collision checks against a simulated world's exact geometry (sim::WorldScene::signedDistance)
// behind the planners' CollisionChecker interface: the teach flight is shaped by
// plan::makeTrajectory against the truth, as a pilot who sees the room would fly it. A sphere is
// free when the true distance from its centre to every surface is at least its radius; unknown
// space does not exist here (UnknownPolicy is ignored).
// Thread safety: not thread safe (counts its tests); the scene must outlive the checker.
#include "strata/plan/collision_checker.h"
#include "strata/sim/world/world_scene.h"

namespace strata::repeat {

class TruthChecker final : public plan::CollisionChecker {
 public:
  /// `step_m` plays the voxel (capsules are tested every step_m / 2); spheres larger than
  /// max_distance_m are never free, as with an ESDF.
  explicit TruthChecker(const sim::WorldScene& scene, float step_m = 0.05f,
                        float max_distance_m = 2.0f);

  std::vector<std::uint8_t> spheresFree(const std::vector<Eigen::Vector3f>& centres_W,
                                        float radius_m, UnknownPolicy unknown) override;
  std::vector<EsdfSample> sample(const std::vector<Eigen::Vector3f>& points_W) override;
  float voxelSize() const override { return step_m_; }
  float maxDistance() const override { return max_distance_m_; }

 private:
  const sim::WorldScene& scene_;
  float step_m_;
  float max_distance_m_;
};

}  // namespace strata::repeat
