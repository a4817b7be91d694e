#pragma once
// What every planner of strata::plan takes and returns: a start and a goal in the world frame, a
// spherical robot, how unknown space counts, and the path found (a polyline, world frame, metres).
// Planners: grid A* (grid_astar.h), RRT* on OMPL (rrt_planner.h), the topological map
// (topo_map.h). docs/plan.md.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "strata/esdf/esdf_query.h"

namespace strata::plan {

struct PlanRequest {
  Eigen::Vector3f start_W = Eigen::Vector3f::Zero();
  Eigen::Vector3f goal_W = Eigen::Vector3f::Zero();
  /// The robot is a sphere of this radius (metres); a path is free when the swept sphere is.
  float radius_m = 0.3f;
  /// kOccupied (safe: unknown space may hold an obstacle) or kFree (optimistic, exploration).
  UnknownPolicy unknown = UnknownPolicy::kOccupied;
  /// Wall-clock budget of sampling planners (seconds); exact planners ignore it.
  double time_budget_s = 1.0;
  /// Seed of sampling planners: the same seed, map and request give the same path.
  std::uint64_t seed = 1;
};

struct PlanResult {
  bool success = false;
  /// Why there is no path (start or goal in collision, not connected, out of time), or empty.
  std::string message;
  /// start_W ... goal_W; empty without success.
  std::vector<Eigen::Vector3f> path_W;
  double length_m = 0.0;
  /// Smallest ESDF distance along the path (sampled every half voxel), metres.
  double min_clearance_m = 0.0;
  /// Wall-clock time of the query (not of building the planner's structures), milliseconds.
  double planning_ms = 0.0;
  /// Sphere tests the query ran (device or host).
  std::uint64_t collision_checks = 0;
};

/// Sum of segment lengths (metres); 0 for fewer than two points.
double pathLength(const std::vector<Eigen::Vector3f>& path_W);

/// A planner on one map. Building its structures (a grid, a graph) happens in its constructor or
/// factory and is not part of PlanResult::planning_ms.
/// Thread safety: not thread safe.
class Planner {
 public:
  virtual ~Planner() = default;
  virtual PlanResult plan(const PlanRequest& request) = 0;
  /// "grid", "rrt", "topo".
  virtual std::string name() const = 0;
  /// Memory of the planner's own structures (bytes), for comparisons; 0 when it keeps none.
  virtual std::size_t memoryBytes() const { return 0; }
};

}  // namespace strata::plan
