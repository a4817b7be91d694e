#include "explore/exploration_truth.h"

// NOTE: the temporary stand-in; becomes "eval/exploration_truth.h" once that is merged.
#include "explore/internal/exploration_truth_fallback.h"

namespace strata::explore {

struct ExplorationTruth::Reachable {
  eval::ReachableSpace space;
};

ExplorationTruth::ExplorationTruth(const sim::World& world, const Eigen::AlignedBox3f& bounds_W,
                                   const Eigen::Vector3f& start_W, float voxel_size_m)
    : scene_(world.buildScene(0)), reachable_(std::make_unique<Reachable>()) {
  reachable_->space = eval::computeReachableSpace(*scene_, bounds_W, start_W, voxel_size_m);
}

ExplorationTruth::~ExplorationTruth() = default;

double ExplorationTruth::exploredFraction(const TsdfMap& map, float min_weight) const {
  return eval::exploredFraction(reachable_->space, map, min_weight);
}

float ExplorationTruth::minClearance(const std::vector<Eigen::Vector3f>& positions_W) const {
  return eval::minClearanceAlong(*scene_, positions_W);
}

float ExplorationTruth::clearance(const Eigen::Vector3f& p_W) const {
  return scene_->signedDistance(p_W);
}

std::size_t ExplorationTruth::reachableVoxels() const { return reachable_->space.voxels.size(); }

}  // namespace strata::explore
