// Planners by name (contract in planner_factory.h).
#include "strata/plan/planner_factory.h"

#include <cmath>
#include <cstdio>

#include "strata/core/error.h"
#include "strata/plan/grid_astar.h"
#include "strata/plan/rrt_planner.h"
#include "strata/plan/topo_planner.h"

namespace strata::plan {

std::unique_ptr<Planner> makePlanner(const std::string& name, const EsdfMap& esdf,
                                     CollisionChecker& checker, const PlannerOptions& options) {
  if (!std::isfinite(options.radius_m) || options.radius_m < 0.0f) {
    throw InputError("robot radius must be finite and >= 0");
  }
  if (options.radius_m >= esdf.config.max_distance_m) {
    throw InputError("robot radius " + std::to_string(options.radius_m) +
                     " m is not below the ESDF's max distance " +
                     std::to_string(esdf.config.max_distance_m) +
                     " m: no sphere could be free (raise the ESDF max distance)");
  }
  if (name == "grid") {
    auto grid = std::make_unique<GridAStarPlanner>(esdf, checker);
    grid->prepare(options.radius_m, options.unknown);
    return grid;
  }
  if (name == "topo") {
    return std::make_unique<TopoPlanner>(esdf, checker,
                                         TopoOptions{options.radius_m, options.unknown});
  }
  if (name == "rrt") {
    RrtOptions rrt;
    rrt.bounds_W = esdfBounds(esdf);
    if (rrt.bounds_W.isEmpty()) throw InputError("planner 'rrt': the map is empty");
    return std::make_unique<RrtPlanner>(checker, rrt);
  }
  throw InputError("unknown planner '" + name + "' (grid, topo, rrt)");
}

std::string endpointProblem(const EsdfMap& esdf, CollisionChecker& checker, const char* what,
                            const Eigen::Vector3f& p_W, float radius_m, UnknownPolicy unknown) {
  if (!p_W.allFinite()) return std::string(what) + " is not a finite point";
  const Eigen::Vector3i v = (p_W / esdf.voxel_size_m).array().floor().cast<int>();
  if (!allocatedBounds(esdf).contains(v)) {
    const VoxelBox b = allocatedBounds(esdf);
    char text[200];
    std::snprintf(text, sizeof(text),
                  " is outside the map (x %.2f..%.2f, y %.2f..%.2f, z %.2f..%.2f m)",
                  b.lo.x() * esdf.voxel_size_m, (b.hi.x() + 1) * esdf.voxel_size_m,
                  b.lo.y() * esdf.voxel_size_m, (b.hi.y() + 1) * esdf.voxel_size_m,
                  b.lo.z() * esdf.voxel_size_m, (b.hi.z() + 1) * esdf.voxel_size_m);
    return describePoint(what, p_W) +
           (b.empty() ? std::string(" is outside the map (it is empty)") : std::string(text));
  }
  if (checker.spheresFree({voxelCenter(v, esdf.voxel_size_m)}, radius_m, unknown)[0] == 0) {
    char text[160];
    std::snprintf(text, sizeof(text), " is in collision (robot radius %.2f m, unknown space %s)",
                  static_cast<double>(radius_m),
                  unknown == UnknownPolicy::kOccupied ? "occupied" : "free");
    return describePoint(what, p_W) + text;
  }
  return "";
}

double plannerBuildMs(const Planner& planner) {
  if (const auto* grid = dynamic_cast<const GridAStarPlanner*>(&planner)) {
    return grid->buildStats().build_ms;
  }
  if (const auto* topo = dynamic_cast<const TopoPlanner*>(&planner)) {
    return topo->map().stats().build_ms;
  }
  return 0.0;
}

}  // namespace strata::plan
