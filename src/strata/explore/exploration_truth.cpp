#include "strata/explore/exploration_truth.h"

#include "strata/explore/reachable_space.h"

namespace strata::explore {

struct ExplorationTruth::Reachable {
  ReachableSpace space;
};

ExplorationTruth::ExplorationTruth(const sim::World& world, const Eigen::AlignedBox3f& bounds_W,
                                   const Eigen::Vector3f& start_W, float voxel_size_m)
    : scene_(world.buildScene(0)), reachable_(std::make_unique<Reachable>()) {
  reachable_->space =
      explore::computeReachableSpace(*scene_, bounds_W.cast<double>(), start_W.cast<double>(),
                                  static_cast<double>(voxel_size_m));
}

ExplorationTruth::~ExplorationTruth() = default;

double ExplorationTruth::exploredFraction(const TsdfMap& map, float min_weight) const {
  return explore::exploredFraction(reachable_->space, map, min_weight);
}

float ExplorationTruth::minClearance(const std::vector<Eigen::Vector3f>& positions_W) const {
  std::vector<Eigen::Vector3d> positions;
  positions.reserve(positions_W.size());
  for (const Eigen::Vector3f& p : positions_W) positions.push_back(p.cast<double>());
  const double clearance_m = explore::minClearanceAlong(*scene_, positions);
  // The distance to the nearest surface is unsigned: a position inside a solid reads negative.
  for (const Eigen::Vector3f& p : positions_W) {
    if (scene_->occupied(p)) return -static_cast<float>(scene_->distanceToSurface(p.cast<double>()));
  }
  return static_cast<float>(clearance_m);
}

float ExplorationTruth::clearance(const Eigen::Vector3f& p_W) const {
  return scene_->signedDistance(p_W);
}

std::size_t ExplorationTruth::reachableVoxels() const { return reachable_->space.reachable_count; }

}  // namespace strata::explore
