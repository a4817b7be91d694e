#pragma once
// The history-aware next-best-view planner (Selin et al., RA-L 2019, "autonomous exploration
// planner"; Publication V of the thesis). Local step: the receding-horizon RRT of the baseline
// (local_tree.h), but every node's yaw is the best of the full circle (ViewGain::best_yaw_rad,
// all nodes in one batched gain call) instead of a random one. History: nodes of high gain that
// the robot does not fly to are cached in a graph of known-free segments (HistoryGraph) together
// with the positions the robot visited. When the best local gain falls below local_gain_m3 (a
// dead end, an explored room), the planner picks the cached view of the best
// gain / (path length + distance_offset_m) and flies the graph's shortest path there. Cached
// gains are re-evaluated lazily: gains only shrink as the map fills, so a stored gain bounds the
// current one and candidates are re-evaluated best bound first, in batches, until the best
// current score beats every remaining bound; views below prune_gain_m3 are dropped. When
// neither the tree nor the cache has gain, a global step samples the whole bounds for views in
// known free space that the graph can reach (HistoryConfig::global_samples); the run ends only
// when that finds none either. Half the tree's samples span the bounds' whole height.
// Parameters (HistoryConfig) are documented in docs/explore.md, "Planners".
// Thread safety: not thread safe.
#include <cstdint>
#include <map>
#include <random>

#include "strata/explore/exploration_planner.h"
#include "strata/explore/history_graph.h"
#include "strata/explore/local_tree.h"

namespace strata::explore {

struct HistoryConfig {
  /// The local tree; half its samples span the bounds' whole height (full_height_share).
  LocalTreeConfig tree = tallTree();
  /// Below this best local view gain (m^3) the planner goes to a cached view.
  float local_gain_m3 = 1.0f;
  /// Nodes whose view gains at least this (m^3) are cached.
  float cache_gain_m3 = 1.5f;
  /// A cached view whose re-evaluated gain is below this (m^3) is dropped.
  float prune_gain_m3 = 0.5f;
  /// No local view and no cached view above this (m^3): exploration is over.
  float done_gain_m3 = 0.2f;
  /// Steps in a row without local or cached gain that end the run.
  int done_steps = 3;
  /// Score of a cached view = gain / (graph distance + this) (metres).
  float distance_offset_m = 1.0f;
  /// Cached views re-evaluated per gain call.
  int reevaluate_batch = 8;
  /// A new cached view within this of a cached one is not added (metres).
  float cache_spacing_m = 0.75f;
  /// Visited positions are joined to graph nodes within this (checked shortcuts, metres)...
  float shortcut_radius_m = 2.0f;
  /// ... at most this many per step.
  int shortcut_count = 6;
  /// Global step: with no local and no cached view left, this many positions are drawn over
  /// the whole bounds; those in known free space whose view gains at least cache_gain_m3 and
  /// that join the graph by a free segment (to a node within global_join_radius_m) become
  /// cached views. The run ends ("no gain") only when this finds none either.
  int global_samples = 96;
  float global_join_radius_m = 3.0f;
  std::uint64_t seed = 1;

  static LocalTreeConfig tallTree();
  /// Throws InputError naming the bad field.
  void validate() const;
};

class HistoryPlanner final : public ExplorationPlanner {
 public:
  explicit HistoryPlanner(const HistoryConfig& config);
  ExplorationStep plan(const ExplorationState& state) override;
  std::string name() const override { return "history"; }

  const HistoryGraph& graph() const { return graph_; }
  /// Cached views: graph node -> gain (m^3) as last evaluated.
  std::map<int, float> cachedGains() const;

 private:
  struct CachedView {
    float gain_m3 = 0.0f;
    float yaw_rad = 0.0f;
  };

  /// The graph node of the robot's position, adding it (and checked edges) when new.
  int locate(const ExplorationState& state);
  void cacheViews(const LocalTree& tree, int root_node);
  /// The cached view to go to (-1: none worth it); `distance` from shortestFrom.
  int pickCached(const ExplorationState& state, const std::vector<double>& distance,
                 std::size_t& evaluations);
  /// The global step (HistoryConfig::global_samples): cached views added.
  int sampleGlobalViews(const ExplorationState& state, std::size_t& evaluations);
  /// A cached view to fly to now (the step's path and mode set), or false.
  bool goToCachedView(const ExplorationState& state, int here, ExplorationStep& step);
  /// The checked graph path from `here` to `target` (empty when none stays free).
  std::vector<int> freeGraphPath(const ExplorationState& state, int here, int target);

  HistoryConfig config_;
  std::mt19937_64 rng_;
  HistoryGraph graph_;
  std::map<int, CachedView> cache_;
  int last_node_ = -1;            // where the robot was at the previous step
  int target_node_ = -1;          // where the previous step sent it
  std::vector<int> global_path_;  // remaining nodes of a path to a cached view
  std::vector<Eigen::Vector3f> previous_branch_W_;
  int steps_without_gain_ = 0;
  int empty_trees_ = 0;  // steps in a row whose tree found no free edge
  /// The last path issued, from where the robot stood then (the way back when it is pinned).
  std::vector<Eigen::Vector3f> route_W_;
  void rememberRoute(const ExplorationState& state, const std::vector<Waypoint>& path);
  std::vector<Waypoint> retraceRoute(const ExplorationState& state) const;
};

}  // namespace strata::explore
