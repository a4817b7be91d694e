#include "strata/explore/nbvp_planner.h"

#include <algorithm>

#include "strata/core/error.h"

namespace strata::explore {

void NbvpConfig::validate() const {
  tree.validate();
  if (!(done_gain_m3 >= 0.0f)) throw InputError("nbvp done_gain_m3 must be >= 0");
  if (done_steps < 1) throw InputError("nbvp done_steps must be >= 1");
  if (tolerance_nodes < tree.nodes) throw InputError("nbvp tolerance_nodes must be >= nodes");
}

NbvpPlanner::NbvpPlanner(const NbvpConfig& config) : config_(config), rng_(config.seed) {
  config_.validate();
}

std::size_t NbvpPlanner::evaluate(LocalTree& tree, std::size_t first,
                                  const ExplorationState& state) {
  std::vector<Eigen::Vector3f> positions;
  for (std::size_t i = first; i < tree.size(); ++i) positions.push_back(tree.nodes()[i].position_W);
  if (positions.empty()) return 0;
  const std::vector<ViewGain> gains = state.gain(positions);
  std::uniform_real_distribution<float> yaw(-3.14159265f, 3.14159265f);
  for (std::size_t i = first; i < tree.size(); ++i) {
    TreeNode& node = tree.nodes()[i];
    node.yaw_rad = yaw(rng_);
    node.gain_m3 = gainAtYaw(gains[i - first], state.gain_config, node.yaw_rad);
  }
  return positions.size();
}

ExplorationStep NbvpPlanner::plan(const ExplorationState& state) {
  ExplorationStep step;
  LocalTree tree(state.pose.position_W);
  tree.seedBranch(previous_branch_W_, *state.checker, state.check_radius_m);
  const Eigen::AlignedBox3f box =
      localBox(state.pose.position_W, config_.tree.half_extent_m, state.bounds_W);
  tree.grow(config_.tree.nodes, box, config_.tree, *state.checker, state.check_radius_m, rng_);
  step.gain_evaluations = evaluate(tree, 1, state);
  tree.score(config_.tree.lambda_per_m);
  // No gain nearby: grow on over the whole bounds, up to the tolerance.
  if (tree.nodes()[tree.best()].score_m3 < config_.done_gain_m3) {
    const std::size_t first = tree.size();
    LocalTreeConfig wide = config_.tree;
    wide.max_batches = config_.tree.max_batches * config_.tolerance_nodes / config_.tree.nodes;
    tree.grow(config_.tolerance_nodes, state.bounds_W, wide, *state.checker, state.check_radius_m,
              rng_);
    step.gain_evaluations += evaluate(tree, first, state);
    tree.score(config_.tree.lambda_per_m);
  }
  step.tree_nodes = tree.size() - 1;
  for (std::size_t i = 1; i < tree.size(); ++i) {
    step.best_gain_m3 = std::max(step.best_gain_m3, tree.nodes()[i].gain_m3);
  }
  const int best = tree.best();
  previous_branch_W_.clear();
  if (best == 0) return step;  // no free edge at all: hover, the loop asks again
  const bool no_gain = tree.nodes()[best].score_m3 < config_.done_gain_m3;
  steps_without_gain_ = no_gain ? steps_without_gain_ + 1 : 0;
  if (steps_without_gain_ >= config_.done_steps) {
    step.finished = true;
    return step;
  }
  const std::vector<int> branch = tree.branch(best);
  const TreeNode& first = tree.nodes()[branch.front()];
  step.path.push_back({first.position_W, first.yaw_rad});
  for (std::size_t i = 1; i < branch.size(); ++i) {
    previous_branch_W_.push_back(tree.nodes()[branch[i]].position_W);
  }
  step.mode = "local";
  return step;
}

}  // namespace strata::explore
