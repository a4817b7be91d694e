// Queries on the topological map (contract in topo_planner.h).
#include "strata/plan/topo_planner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "strata/plan/grid_astar.h"
#include "strata/core/clock.h"

namespace strata::plan {
namespace {

using Clock = SteadyClock;

/// The point of the portal's plane on the straight line from `prev` to `next` (with `next`
/// mirrored to the far side when both lie on one side), clamped to the portal's rectangle.
Eigen::Vector3f crossing(const TopoPortal& p, const Eigen::Vector3f& prev,
                         const Eigen::Vector3f& next) {
  const float plane = p.lo_W[p.axis];
  const float d_prev = std::abs(prev[p.axis] - plane), d_next = std::abs(next[p.axis] - plane);
  const float t = d_prev + d_next > 0.0f ? d_prev / (d_prev + d_next) : 0.5f;
  Eigen::Vector3f x = prev + t * (next - prev);
  x[p.axis] = plane;
  return x.cwiseMax(p.lo_W).cwiseMin(p.hi_W);
}

// Landmarks the search reads at most (TopoOptions::landmarks beyond this are ignored).
constexpr int kMaxLandmarks = 32;

struct OpenNode {
  float f;
  std::int32_t node;
  bool operator>(const OpenNode& o) const { return f > o.f; }
};

}  // namespace

struct TopoPlanner::Scratch {
  std::vector<float> g;
  std::vector<std::int32_t> parent;
  std::vector<float> h;               // heuristic, computed once per node and query
  std::vector<std::uint32_t> seen;    // == generation: g and parent are this query's
  std::vector<std::uint32_t> closed;  // == generation: expanded in this query
  std::vector<OpenNode> open;         // a binary heap (std::push_heap), kept for its capacity
  std::uint32_t generation = 0;
  std::uint64_t expanded = 0;  // portals expanded by the last query

  void reset(std::size_t nodes) {
    expanded = 0;
    if (g.size() != nodes) {
      g.assign(nodes, 0.0f);
      parent.assign(nodes, -1);
      h.assign(nodes, 0.0f);
      seen.assign(nodes, 0);
      closed.assign(nodes, 0);
      generation = 0;
    }
    ++generation;
    open.clear();
  }
};

namespace {

/// A* over the portal graph from `start` in cluster `from` to `goal` in cluster `to`: the
/// portals crossed, in order; false when not connected.
bool searchPortals(const TopoMap& map, const Eigen::Vector3f& start, std::int32_t from,
                   const Eigen::Vector3f& goal, std::int32_t to, TopoPlanner::Scratch& s,
                   std::vector<const TopoPortal*>* route) {
  const auto& portals = map.portals();
  const std::vector<Eigen::Vector3f>& centres = map.portalCentres();
  const auto goal_node = static_cast<std::int32_t>(portals.size());  // the start: parent -1
  s.reset(portals.size() + 1);
  const std::uint32_t gen = s.generation;
  // Graph distances from each landmark to the goal (through the goal cluster's portals).
  const TopoLandmarks& marks = map.landmarks();
  float to_goal[kMaxLandmarks];
  const int landmark_count = std::min(marks.count(), kMaxLandmarks);
  for (int l = 0; l < landmark_count; ++l) {
    to_goal[l] = std::numeric_limits<float>::infinity();
    for (const std::int32_t* p = map.portalsBegin(to); p != map.portalsEnd(to); ++p) {
      to_goal[l] = std::min(to_goal[l], marks.distance(l, *p) +
                                            (centres[static_cast<std::size_t>(*p)] - goal).norm());
    }
  }
  const auto lowerBound = [&](std::int32_t node, const Eigen::Vector3f& at) {
    float h = (at - goal).norm();
    for (int l = 0; l < landmark_count; ++l) {
      const float d = marks.distance(l, node);
      if (std::isfinite(d) && std::isfinite(to_goal[l])) h = std::max(h, std::abs(to_goal[l] - d));
    }
    return h;
  };
  const auto relax = [&](std::int32_t node, std::int32_t via, float cost,
                         const Eigen::Vector3f& at) {
    const auto i = static_cast<std::size_t>(node);
    if (s.closed[i] == gen || (s.seen[i] == gen && cost >= s.g[i])) return;
    if (s.seen[i] != gen) s.h[i] = node == goal_node ? 0.0f : lowerBound(node, at);
    s.g[i] = cost;
    s.parent[i] = via;
    s.seen[i] = gen;
    s.open.push_back({cost + s.h[i], node});
    std::push_heap(s.open.begin(), s.open.end(), std::greater<OpenNode>());
  };
  const auto expandCluster = [&](std::int32_t c, std::int32_t via, float base,
                                 const Eigen::Vector3f& at) {
    for (const std::int32_t* p = map.portalsBegin(c); p != map.portalsEnd(c); ++p) {
      const Eigen::Vector3f& centre = centres[static_cast<std::size_t>(*p)];
      relax(*p, via, base + (centre - at).norm(), centre);
    }
    if (c == to) relax(goal_node, via, base + (goal - at).norm(), goal);
  };
  expandCluster(from, -1, 0.0f, start);
  while (!s.open.empty()) {
    std::pop_heap(s.open.begin(), s.open.end(), std::greater<OpenNode>());
    const OpenNode top = s.open.back();
    s.open.pop_back();
    const auto i = static_cast<std::size_t>(top.node);
    if (s.closed[i] == gen) continue;
    s.closed[i] = gen;
    ++s.expanded;
    if (top.node == goal_node) break;
    const TopoPortal& p = portals[i];
    expandCluster(p.a, top.node, s.g[i], centres[i]);
    expandCluster(p.b, top.node, s.g[i], centres[i]);
  }
  if (s.closed[static_cast<std::size_t>(goal_node)] != gen) return false;
  route->clear();
  for (std::int32_t v = s.parent[static_cast<std::size_t>(goal_node)]; v >= 0;
       v = s.parent[static_cast<std::size_t>(v)]) {
    route->push_back(&portals[static_cast<std::size_t>(v)]);
  }
  std::reverse(route->begin(), route->end());
  return true;
}

std::string locateProblem(const TopoMap& map, const char* what, const Eigen::Vector3f& p_W,
                          std::int32_t* cluster) {
  if (!p_W.allFinite()) return std::string(what) + " is not a finite point";
  const Eigen::Vector3i v = (p_W / map.voxelSize()).array().floor().cast<int>();
  if (!map.bounds().contains(v)) return describePoint(what, p_W) + " is outside the map";
  *cluster = map.clusterAt(v);
  if (*cluster >= 0) return "";
  char text[160];
  std::snprintf(text, sizeof(text), " is in collision (robot radius %.2f m, unknown space %s)",
                static_cast<double>(map.options().radius_m),
                map.options().unknown == UnknownPolicy::kOccupied ? "occupied" : "free");
  return describePoint(what, p_W) + text;
}

}  // namespace

std::vector<Eigen::Vector3f> pullThroughPortals(const Eigen::Vector3f& start_W,
                                                const std::vector<const TopoPortal*>& portals,
                                                const Eigen::Vector3f& goal_W, int sweeps) {
  std::vector<Eigen::Vector3f> path{start_W};
  for (const TopoPortal* p : portals) path.push_back(p->centre());
  path.push_back(goal_W);
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    float moved = 0.0f;
    for (std::size_t i = 1; i + 1 < path.size(); ++i) {
      const Eigen::Vector3f x = crossing(*portals[i - 1], path[i - 1], path[i + 1]);
      moved = std::max(moved, (x - path[i]).norm());
      path[i] = x;
    }
    if (moved < 1e-6f) break;
  }
  // Crossing points that fell on a straight line add nothing.
  std::vector<Eigen::Vector3f> out{path.front()};
  for (std::size_t i = 1; i + 1 < path.size(); ++i) {
    const Eigen::Vector3f a = out.back() - path[i], b = path[i + 1] - path[i];
    if (a.norm() < 1e-6f || b.norm() < 1e-6f) continue;
    if (a.normalized().dot(b.normalized()) < -1.0f + 1e-7f) continue;
    out.push_back(path[i]);
  }
  out.push_back(path.back());
  return out;
}

TopoPlanner::TopoPlanner(const EsdfMap& esdf, CollisionChecker& checker, const TopoOptions& options)
    : esdf_(esdf),
      checker_(checker),
      map_(std::make_unique<TopoMap>(esdf, options)),
      scratch_(std::make_unique<Scratch>()) {}

TopoPlanner::~TopoPlanner() = default;

std::uint64_t TopoPlanner::lastExpanded() const { return scratch_->expanded; }

PlanResult TopoPlanner::plan(const PlanRequest& request) {
  PlanResult result;
  if (!std::isfinite(request.radius_m) || request.radius_m < 0.0f) {
    result.message = "robot radius must be finite and >= 0";
    return result;
  }
  if (request.radius_m != map_->options().radius_m || request.unknown != map_->options().unknown) {
    map_ = std::make_unique<TopoMap>(esdf_, TopoOptions{request.radius_m, request.unknown});
  }
  const auto start_time = Clock::now();
  std::int32_t from = -1, to = -1;
  result.message = locateProblem(*map_, "start", request.start_W, &from);
  if (result.message.empty()) result.message = locateProblem(*map_, "goal", request.goal_W, &to);
  if (!result.message.empty()) return result;
  std::vector<const TopoPortal*> route;
  if (!searchPortals(*map_, request.start_W, from, request.goal_W, to, *scratch_, &route)) {
    result.message = "no path: start and goal are not connected through free space";
    result.planning_ms = msSince(start_time);
    return result;
  }
  result.path_W = pullThroughPortals(request.start_W, route, request.goal_W);
  result.planning_ms = msSince(start_time);
  result.success = true;
  result.length_m = pathLength(result.path_W);
  result.min_clearance_m = checker_.minClearance(result.path_W);
  return result;
}

}  // namespace strata::plan
