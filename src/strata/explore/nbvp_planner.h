#pragma once
// The baseline: receding-horizon next-best-view planning (Bircher et al., ICRA 2016). Each step
// grows a local RRT through known free space (local_tree.h), gives every node a uniformly random
// yaw, scores branches by their discounted accumulated gain and flies only the first edge of the
// best branch; the rest of that branch re-seeds the next step's tree, the planner's only memory.
// When the best score stays below `done_gain_m3`, the tree grows on to `tolerance_nodes` over the
// whole bounds; still nothing, the robot takes the best branch's first edge anyway, and after
// `done_steps` such steps in a row exploration is over (the paper's termination rule, made
// patient so a momentary dead spot does not end the run).
// Thread safety: not thread safe.
#include <cstdint>
#include <random>

#include "strata/explore/exploration_planner.h"
#include "strata/explore/local_tree.h"

namespace strata::explore {

struct NbvpConfig {
  LocalTreeConfig tree;
  /// Below this best score (m^3) the step counts as without gain.
  float done_gain_m3 = 0.2f;
  /// Nodes the tree may grow to (over the whole bounds) before a step without gain ends the run.
  int tolerance_nodes = 120;
  /// Steps in a row without gain that end the run.
  int done_steps = 3;
  std::uint64_t seed = 1;

  /// Throws InputError naming the bad field.
  void validate() const;
};

class NbvpPlanner final : public ExplorationPlanner {
 public:
  explicit NbvpPlanner(const NbvpConfig& config);
  ExplorationStep plan(const ExplorationState& state) override;
  std::string name() const override { return "nbvp"; }

 private:
  /// Gains of nodes [first, size) at random yaws.
  std::size_t evaluate(LocalTree& tree, std::size_t first, const ExplorationState& state);

  NbvpConfig config_;
  std::mt19937_64 rng_;
  std::vector<Eigen::Vector3f> previous_branch_W_;
  int steps_without_gain_ = 0;
};

}  // namespace strata::explore
