#pragma once
// Planners by name, for the programs (`strata plan`, `strata-bench plan`): "grid" (grid A*,
// grid_astar.h), "topo" (the topological map, topo_planner.h), "rrt" (RRT* on OMPL,
// rrt_planner.h, sampled in the allocated map's bounds). A planner's structures are built here for the options' robot, so
// the first query does not pay for them; plannerBuildMs() reports that time.
// Thread safety: as the planners (not thread safe).
#include <memory>
#include <string>

#include "strata/plan/collision_checker.h"
#include "strata/plan/plan_types.h"

namespace strata::plan {

struct PlannerOptions {
  /// The robot the structures are built for (a query with another radius or policy rebuilds).
  float radius_m = 0.3f;
  UnknownPolicy unknown = UnknownPolicy::kOccupied;
};

/// The planner `name` on `esdf` (host copy) through `checker`; both must outlive it.
/// InputError for an unknown name, a planner this build lacks, or a bad radius.
std::unique_ptr<Planner> makePlanner(const std::string& name, const EsdfMap& esdf,
                                     CollisionChecker& checker, const PlannerOptions& options);

/// Why `p_W` cannot be a start or goal ("" when it can): not finite, outside the allocated
/// blocks' bounds, or the robot sphere at its voxel centre not free (the planners' rule).
std::string endpointProblem(const EsdfMap& esdf, CollisionChecker& checker, const char* what,
                            const Eigen::Vector3f& p_W, float radius_m, UnknownPolicy unknown);

/// Milliseconds spent building the planner's structures (grid, graph); 0 for one that keeps none.
double plannerBuildMs(const Planner& planner);

}  // namespace strata::plan
