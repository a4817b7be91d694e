#include "strata/explore/history_planner.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "strata/core/error.h"

namespace strata::explore {
namespace {

constexpr float kSamePlaceM = 0.05f;

bool finiteNonNegative(float v) { return std::isfinite(v) && v >= 0.0f; }

/// Fills every non-root node's yaw and gain with the best of the full circle (one gain call).
std::size_t evaluateBestYaw(LocalTree& tree, const ExplorationState& state) {
  std::vector<Eigen::Vector3f> positions;
  for (std::size_t i = 1; i < tree.size(); ++i) positions.push_back(tree.nodes()[i].position_W);
  if (positions.empty()) return 0;
  const std::vector<ViewGain> gains = state.gain(positions);
  for (std::size_t i = 1; i < tree.size(); ++i) {
    tree.nodes()[i].yaw_rad = gains[i - 1].best_yaw_rad;
    tree.nodes()[i].gain_m3 = gains[i - 1].best_gain_m3;
  }
  return positions.size();
}

float bestNodeGain(const LocalTree& tree) {
  float best = 0.0f;
  for (std::size_t i = 1; i < tree.size(); ++i) best = std::max(best, tree.nodes()[i].gain_m3);
  return best;
}

}  // namespace

LocalTreeConfig HistoryConfig::tallTree() {
  LocalTreeConfig tree;
  tree.full_height_share = 0.5f;
  return tree;
}

void HistoryConfig::validate() const {
  tree.validate();
  if (global_samples < 0) throw InputError("history global_samples must be >= 0");
  if (!(global_join_radius_m > 0.0f) || !std::isfinite(global_join_radius_m)) {
    throw InputError("history global_join_radius_m must be > 0");
  }
  for (float v : {local_gain_m3, cache_gain_m3, prune_gain_m3, done_gain_m3, distance_offset_m,
                  cache_spacing_m, shortcut_radius_m}) {
    if (!finiteNonNegative(v)) throw InputError("history planner: gains and distances >= 0");
  }
  if (distance_offset_m <= 0.0f) throw InputError("history distance_offset_m must be > 0");
  if (done_steps < 1) throw InputError("history done_steps must be >= 1");
  if (reevaluate_batch < 1) throw InputError("history reevaluate_batch must be >= 1");
  if (shortcut_count < 0) throw InputError("history shortcut_count must be >= 0");
}

HistoryPlanner::HistoryPlanner(const HistoryConfig& config) : config_(config), rng_(config.seed) {
  config_.validate();
}

std::map<int, float> HistoryPlanner::cachedGains() const {
  std::map<int, float> out;
  for (const auto& [node, view] : cache_) out[node] = view.gain_m3;
  return out;
}

int HistoryPlanner::locate(const ExplorationState& state) {
  const Eigen::Vector3f& p = state.pose.position_W;
  if (target_node_ >= 0 && (graph_.position(target_node_) - p).norm() < kSamePlaceM) {
    return target_node_;
  }
  for (int node : global_path_) {
    if ((graph_.position(node) - p).norm() < kSamePlaceM) return node;
  }
  const int here = graph_.addNode(p);
  // Join the new position to the graph where the segments are free (one checker call).
  std::vector<int> others =
      graph_.near(p, config_.shortcut_radius_m, static_cast<std::size_t>(config_.shortcut_count));
  others.erase(std::remove(others.begin(), others.end(), here), others.end());
  if (last_node_ >= 0 && std::find(others.begin(), others.end(), last_node_) == others.end()) {
    others.push_back(last_node_);
  }
  std::vector<EsdfSegment> segments;
  for (int other : others) segments.push_back({p, graph_.position(other)});
  const std::vector<std::uint8_t> free =
      state.checker->segmentsFree(segments, state.check_radius_m, UnknownPolicy::kOccupied);
  for (std::size_t i = 0; i < others.size(); ++i) {
    if (free[i]) graph_.addEdge(here, others[i]);
  }
  return here;
}

void HistoryPlanner::cacheViews(const LocalTree& tree, int root_node) {
  std::vector<int> graph_id(tree.size(), -1);
  graph_id[0] = root_node;
  // Parents precede children in the tree, so a node's ancestors get their ids first.
  auto ensure = [&](int n, auto&& self) -> int {
    if (graph_id[n] >= 0) return graph_id[n];
    const int parent = self(tree.nodes()[n].parent, self);
    graph_id[n] = graph_.addNode(tree.nodes()[n].position_W);
    graph_.addEdge(parent, graph_id[n]);
    return graph_id[n];
  };
  for (std::size_t i = 1; i < tree.size(); ++i) {
    const TreeNode& node = tree.nodes()[i];
    if (node.gain_m3 < config_.cache_gain_m3) continue;
    const bool crowded = std::any_of(cache_.begin(), cache_.end(), [&](const auto& entry) {
      return (graph_.position(entry.first) - node.position_W).norm() < config_.cache_spacing_m;
    });
    if (crowded) continue;
    const int id = ensure(static_cast<int>(i), ensure);
    cache_[id] = {node.gain_m3, node.yaw_rad};
  }
}

int HistoryPlanner::pickCached(const ExplorationState& state, const std::vector<double>& distance,
                               std::size_t& evaluations) {
  struct Candidate {
    int node;
    double bound;
  };
  std::vector<Candidate> candidates;
  for (const auto& [node, view] : cache_) {
    if (std::isfinite(distance[node])) {
      candidates.push_back({node, view.gain_m3 / (distance[node] + config_.distance_offset_m)});
    }
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.bound > b.bound; });
  int best = -1;
  double best_score = -std::numeric_limits<double>::infinity();
  const std::size_t batch = static_cast<std::size_t>(config_.reevaluate_batch);
  for (std::size_t i = 0; i < candidates.size(); i += batch) {
    if (best_score >= candidates[i].bound) break;  // no remaining view can beat it
    const std::size_t end = std::min(candidates.size(), i + batch);
    std::vector<Eigen::Vector3f> positions;
    for (std::size_t k = i; k < end; ++k) positions.push_back(graph_.position(candidates[k].node));
    const std::vector<ViewGain> gains = state.gain(positions);
    evaluations += positions.size();
    for (std::size_t k = i; k < end; ++k) {
      const int node = candidates[k].node;
      const ViewGain& g = gains[k - i];
      if (g.best_gain_m3 < config_.prune_gain_m3) {
        cache_.erase(node);
        continue;
      }
      cache_[node] = {g.best_gain_m3, g.best_yaw_rad};
      const double score = g.best_gain_m3 / (distance[node] + config_.distance_offset_m);
      if (score > best_score) {
        best_score = score;
        best = node;
      }
    }
  }
  return best;
}

int HistoryPlanner::sampleGlobalViews(const ExplorationState& state, std::size_t& evaluations) {
  if (config_.global_samples == 0 || state.bounds_W.isEmpty()) return 0;
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Eigen::Vector3f> drawn;
  for (int i = 0; i < config_.global_samples; ++i) {
    const Eigen::Vector3f t(u(rng_), u(rng_), u(rng_));
    drawn.push_back(state.bounds_W.min() + t.cwiseProduct(state.bounds_W.sizes()));
  }
  const std::vector<std::uint8_t> free =
      state.checker->spheresFree(drawn, state.check_radius_m, UnknownPolicy::kOccupied);
  std::vector<Eigen::Vector3f> known;
  for (std::size_t i = 0; i < drawn.size(); ++i) {
    if (free[i]) known.push_back(drawn[i]);
  }
  if (known.empty()) return 0;
  const std::vector<ViewGain> gains = state.gain(known);
  evaluations += known.size();
  // Joins of the views worth caching to their nearest graph nodes, all in one checker call.
  struct Join {
    std::size_t view;
    int node;
  };
  std::vector<Join> joins;
  std::vector<EsdfSegment> segments;
  for (std::size_t i = 0; i < known.size(); ++i) {
    if (gains[i].best_gain_m3 < config_.cache_gain_m3) continue;
    for (int node : graph_.near(known[i], config_.global_join_radius_m, 4)) {
      joins.push_back({i, node});
      segments.push_back({known[i], graph_.position(node)});
    }
  }
  if (segments.empty()) return 0;
  const std::vector<std::uint8_t> joined =
      state.checker->segmentsFree(segments, state.check_radius_m, UnknownPolicy::kOccupied);
  int added = 0;
  std::vector<int> id(known.size(), -1);
  for (std::size_t k = 0; k < joins.size(); ++k) {
    if (!joined[k]) continue;
    const std::size_t i = joins[k].view;
    if (id[i] < 0) {
      id[i] = graph_.addNode(known[i]);
      cache_[id[i]] = {gains[i].best_gain_m3, gains[i].best_yaw_rad};
      ++added;
    }
    graph_.addEdge(id[i], joins[k].node);
  }
  return added;
}

bool HistoryPlanner::goToCachedView(const ExplorationState& state, int here,
                                    ExplorationStep& step) {
  std::vector<int> parents;
  const std::vector<double> distance = graph_.shortestFrom(here, parents);
  for (int target; (target = pickCached(state, distance, step.gain_evaluations)) >= 0;) {
    const std::vector<int> path = freeGraphPath(state, here, target);
    if (path.empty()) {
      cache_.erase(target);  // not reachable through known free space any more
      continue;
    }
    global_path_.assign(path.begin() + 1, path.end());
    target_node_ = target;
    for (int node : global_path_) step.path.push_back({graph_.position(node), 0.0f});
    // Turn to the cached view's best yaw on the way (the last waypoint's yaw).
    for (Waypoint& w : step.path) w.yaw_rad = cache_[target].yaw_rad;
    step.mode = "global";
    steps_without_gain_ = 0;
    rememberRoute(state, step.path);
    return true;
  }
  return false;
}

std::vector<int> HistoryPlanner::freeGraphPath(const ExplorationState& state, int here,
                                               int target) {
  // Edges were free when added; the map may have changed since, so check the path and route
  // around edges that no longer pass.
  for (int attempt = 0; attempt < 4; ++attempt) {
    std::vector<int> parents;
    graph_.shortestFrom(here, parents);
    const std::vector<int> path = HistoryGraph::pathTo(parents, here, target);
    if (path.size() < 2) return {};
    std::vector<EsdfSegment> segments;
    for (std::size_t i = 1; i < path.size(); ++i) {
      segments.push_back({graph_.position(path[i - 1]), graph_.position(path[i])});
    }
    const std::vector<std::uint8_t> free =
        state.checker->segmentsFree(segments, state.check_radius_m, UnknownPolicy::kOccupied);
    bool all_free = true;
    for (std::size_t i = 0; i < free.size(); ++i) {
      if (!free[i]) {
        graph_.removeEdge(path[i], path[i + 1]);
        all_free = false;
      }
    }
    if (all_free) return path;
  }
  return {};
}

ExplorationStep HistoryPlanner::plan(const ExplorationState& state) {
  ExplorationStep step;
  const int here = locate(state);
  last_node_ = here;
  // On the way to a cached view: fly on.
  const auto at = std::find(global_path_.begin(), global_path_.end(), here);
  if (at != global_path_.end() && at + 1 != global_path_.end()) {
    global_path_.erase(global_path_.begin(), at + 1);
    const float yaw = state.pose.yaw_rad;
    for (int node : global_path_) step.path.push_back({graph_.position(node), yaw});
    step.path.back().yaw_rad = cache_.count(target_node_) ? cache_[target_node_].yaw_rad : yaw;
    step.mode = "continue";
    rememberRoute(state, step.path);
    return step;
  }
  global_path_.clear();
  cache_.erase(here);  // arrived (or passing): its view is being taken now

  LocalTree tree(state.pose.position_W);
  tree.seedBranch(previous_branch_W_, *state.checker, state.check_radius_m);
  tree.grow(config_.tree.nodes,
            localBox(state.pose.position_W, config_.tree.half_extent_m, state.bounds_W),
            fullHeightBox(state.pose.position_W, config_.tree.half_extent_m, state.bounds_W),
            config_.tree, *state.checker, state.check_radius_m, rng_);
  step.gain_evaluations = evaluateBestYaw(tree, state);
  step.tree_nodes = tree.size() - 1;
  tree.score(config_.tree.lambda_per_m);
  step.best_gain_m3 = bestNodeGain(tree);
  const int best = tree.best();
  const std::vector<int> branch = tree.branch(best);
  cacheViews(tree, here);
  previous_branch_W_.clear();

  if (step.best_gain_m3 < config_.local_gain_m3) {
    if (goToCachedView(state, here, step)) return step;
    // Nothing cached: views anywhere in the known free space the graph reaches.
    if (step.best_gain_m3 < config_.done_gain_m3 &&
        sampleGlobalViews(state, step.gain_evaluations) > 0 &&
        goToCachedView(state, here, step)) {
      return step;
    }
    if (step.best_gain_m3 < config_.done_gain_m3 && best > 0) {
      // An empty tree is transient (hover and ask again); a tree without gain counts.
      step.finished = ++steps_without_gain_ >= config_.done_steps;
      if (step.finished) return step;
    }
  }
  if (step.best_gain_m3 >= config_.done_gain_m3) steps_without_gain_ = 0;
  if (best == 0) {
    // No free edge from here: hover and ask again once (a transient), then retrace the route
    // the robot flew here. A warehouse run hovered for good where the map had since put a
    // surface inside the check radius of every edge from the robot; the route it arrived along
    // was flown without a collision moments before (a straight line to an older place need not
    // be: a first version that flew one cut into a rack). Without a route (at the start) it
    // turns in place by a third of a turn instead, so that the camera sees what lies around
    // it: a warehouse start facing a crate hovered there until "stuck".
    if (++empty_trees_ >= 2) {
      empty_trees_ = 0;
      step.path = retraceRoute(state);
      if (!step.path.empty()) {
        step.mode = "back";
      } else {
        constexpr float kTurnRad = 2.0944f;  // 120 degrees
        step.path = {{state.pose.position_W, wrapAngle(state.pose.yaw_rad + kTurnRad)}};
        step.mode = "turn";
      }
    }
    return step;
  }
  empty_trees_ = 0;
  const TreeNode& first = tree.nodes()[branch.front()];
  const int first_node = graph_.addNode(first.position_W);
  graph_.addEdge(here, first_node);
  target_node_ = first_node;
  step.path.push_back({first.position_W, first.yaw_rad});
  for (std::size_t i = 1; i < branch.size(); ++i) {
    previous_branch_W_.push_back(tree.nodes()[branch[i]].position_W);
  }
  step.mode = "local";
  rememberRoute(state, step.path);
  return step;
}

void HistoryPlanner::rememberRoute(const ExplorationState& state,
                                   const std::vector<Waypoint>& path) {
  route_W_.assign(1, state.pose.position_W);
  for (const Waypoint& w : path) route_W_.push_back(w.position_W);
}

std::vector<Waypoint> HistoryPlanner::retraceRoute(const ExplorationState& state) const {
  // Where on the last route the robot stands (it may have stopped at an intermediate waypoint).
  constexpr float kOnRouteM = 0.1f;
  std::size_t at = route_W_.size();
  for (std::size_t i = 0; i < route_W_.size(); ++i) {
    if ((route_W_[i] - state.pose.position_W).norm() < kOnRouteM) at = i;
  }
  std::vector<Waypoint> back;
  if (at == route_W_.size()) return back;
  for (std::size_t i = at; i-- > 0;) back.push_back({route_W_[i], state.pose.yaw_rad});
  return back;
}

}  // namespace strata::explore
