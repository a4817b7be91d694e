#pragma once
// Paths on the topological map (topo_map.h): the start's and the goal's clusters located (their
// voxels must be traversable), A* over the portal graph (nodes: portal centres, plus start and
// goal joined to the portals of their clusters; edges: straight lines across a cluster; heuristic:
// the straight-line distance), then the path through the portals pulled taut: each crossing point
// moved, sweep after sweep, to where the straight line between its neighbours crosses the portal's
// plane, clamped to the portal's rectangle. Every leg stays inside one convex, traversable cluster,
// so the query runs no collision test; PlanResult::min_clearance_m (measured through the checker
// after the clock stops) reports the clearance the path keeps.
// The map is built for the request's (radius, unknown policy) when they differ from the last
// ones (its build time in map().stats(), not in planning_ms).
// Thread safety: not thread safe. The ESDF and the checker must outlive the planner.
#include <memory>

#include "strata/plan/collision_checker.h"
#include "strata/plan/plan_types.h"
#include "strata/plan/topo_map.h"

namespace strata::plan {

class TopoPlanner final : public Planner {
 public:
  /// Builds the map for `options` now.
  TopoPlanner(const EsdfMap& esdf, CollisionChecker& checker, const TopoOptions& options);

  PlanResult plan(const PlanRequest& request) override;
  std::string name() const override { return "topo"; }
  /// The map's graph (clusters, portals, lists, lookup); no per-cell storage.
  std::size_t memoryBytes() const override { return map_->memoryBytes(); }

  ~TopoPlanner() override;

  const TopoMap& map() const { return *map_; }
  /// Portals the last query's search expanded.
  std::uint64_t lastExpanded() const;
  /// After the ESDF changed (topo_map.h).
  void update(const std::vector<BlockIndex>& changed_blocks) {
    map_->update(esdf_, changed_blocks);
  }

  /// Per-node search state kept between queries (internal).
  struct Scratch;

 private:
  const EsdfMap& esdf_;
  CollisionChecker& checker_;
  std::unique_ptr<TopoMap> map_;
  std::unique_ptr<Scratch> scratch_;
};

/// The taut path from `start_W` through `portals` (in order) to `goal_W` (topo_planner.h);
/// `sweeps` passes at most, stopping when no point moves by more than a micrometre.
std::vector<Eigen::Vector3f> pullThroughPortals(const Eigen::Vector3f& start_W,
                                                const std::vector<const TopoPortal*>& portals,
                                                const Eigen::Vector3f& goal_W, int sweeps = 64);

}  // namespace strata::plan
