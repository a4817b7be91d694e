#pragma once
// Grid A*: the shortest 26-connected path over the traversable voxel centres of a host ESDF
// (traversability.h), then line-of-sight pruning with the capsule test (path_prune.h).
//
// Moves: to any of the 26 neighbours, cost = voxel size x {1, sqrt 2, sqrt 3}; a diagonal move is
// allowed only when every voxel of the unit cube it cuts through (the axis-aligned moves around
// it) is traversable too, so the search never squeezes between two blocked voxels and its
// connectivity is the 6-connectivity of the traversable voxels (the topological map's).
// Heuristic: the 3D octile distance (exact cost of the obstacle-free 26-connected path):
// admissible and consistent, so the raw grid path is the shortest on the grid.
// Start and goal are snapped to their voxel centres; the path is start, voxel centres..., goal.
// A start or goal whose voxel centre is not traversable (in collision, or outside the map's
// allocated bounds) gets no path and a message naming it.
//
// The grid is built once per (radius, unknown policy) on the first query that needs it and kept;
// its build time is in buildStats(), not in PlanResult::planning_ms. PlanResult::min_clearance_m
// is measured after the query's clock stops.
// Thread safety: not thread safe. The ESDF and the checker must outlive the planner and not change.
#include <memory>
#include <vector>

#include "strata/plan/collision_checker.h"
#include "strata/plan/plan_types.h"
#include "strata/plan/traversability.h"

namespace strata::plan {

/// Bytes grid A* keeps per cell of the map's bounds: the traversability flag (1) and the search
/// state (g 4, parent 8, two generation stamps 4 + 4).
inline constexpr std::size_t kGridAStarBytesPerCell = 21;

struct GridBuildStats {
  double build_ms = 0.0;  // the last grid built (sphere tests of every cell)
  std::size_t cells = 0;  // of that grid
  std::size_t traversable = 0;
  std::uint64_t expanded = 0;  // cells expanded by the last query
};

class GridAStarPlanner final : public Planner {
 public:
  GridAStarPlanner(const EsdfMap& esdf, CollisionChecker& checker);
  ~GridAStarPlanner() override;

  PlanResult plan(const PlanRequest& request) override;
  std::string name() const override { return "grid"; }
  /// Every cached grid plus the search's scratch: kGridAStarBytesPerCell per cell.
  std::size_t memoryBytes() const override;

  /// The grid for (radius, policy), built now unless cached. InputError for a bad radius.
  const TraversabilityGrid& prepare(float radius_m, UnknownPolicy unknown);
  const GridBuildStats& buildStats() const { return stats_; }

  /// Per-cell search state kept between queries (internal).
  struct Scratch;

 private:
  const EsdfMap& esdf_;
  CollisionChecker& checker_;
  std::vector<std::unique_ptr<TraversabilityGrid>> grids_;
  std::unique_ptr<Scratch> scratch_;
  GridBuildStats stats_;
};

/// "start (1.00, 2.00, 0.50)": a point named for messages.
std::string describePoint(const char* what, const Eigen::Vector3f& p_W);

/// Why a start or goal cannot be used on `grid` ("" when its voxel is traversable).
std::string endpointProblem(const TraversabilityGrid& grid, const char* what,
                            const Eigen::Vector3f& p_W, float voxel_size_m);

}  // namespace strata::plan
