#include "plan_runs.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "strata/core/error.h"
#include "strata/core/statistics.h"
#include "strata/plan/planner_factory.h"

namespace strata::bench {

std::vector<PointPair> reachablePairs(const plan::TraversabilityGrid& grid, float voxel_size_m,
                                      int count, float min_distance_m, std::uint64_t seed) {
  std::int32_t components = 0;
  const std::vector<std::int32_t> label = grid.components(&components);
  std::vector<std::vector<std::int64_t>> members(static_cast<std::size_t>(components));
  std::vector<std::int64_t> all;
  for (std::size_t i = 0; i < label.size(); ++i) {
    if (label[i] < 0) continue;
    members[static_cast<std::size_t>(label[i])].push_back(static_cast<std::int64_t>(i));
    all.push_back(static_cast<std::int64_t>(i));
  }
  std::vector<PointPair> pairs;
  if (all.empty()) return pairs;
  std::mt19937_64 rng(seed);
  const auto centre = [&](std::int64_t cell) {
    return voxelCenter(grid.voxel(cell), voxel_size_m);
  };
  // Bounded tries: a world whose components are all tiny yields fewer pairs, not a hang.
  for (int tries = 0; static_cast<int>(pairs.size()) < count && tries < 100 * count; ++tries) {
    const std::int64_t start =
        all[std::uniform_int_distribution<std::size_t>(0, all.size() - 1)(rng)];
    const auto& same = members[static_cast<std::size_t>(label[static_cast<std::size_t>(start)])];
    const std::int64_t goal =
        same[std::uniform_int_distribution<std::size_t>(0, same.size() - 1)(rng)];
    if ((centre(start) - centre(goal)).norm() < min_distance_m) continue;
    pairs.emplace_back(centre(start), centre(goal));
  }
  return pairs;
}

PlannerRun runPlanner(const std::string& name, const EsdfMap& esdf, float radius_m,
                      const std::vector<PointPair>& pairs) {
  PlannerRun run;
  run.name = name;
  plan::HostCollisionChecker checker(esdf);
  std::unique_ptr<plan::Planner> planner;
  try {
    planner = plan::makePlanner(name, esdf, checker, plan::PlannerOptions{radius_m});
  } catch (const InputError& e) {
    run.note = e.what();
    return run;
  }
  run.built = true;
  run.build_ms = plan::plannerBuildMs(*planner);
  for (const auto& [start, goal] : pairs) {
    plan::PlanRequest request;
    request.start_W = start;
    request.goal_W = goal;
    request.radius_m = radius_m;
    const plan::PlanResult r = planner->plan(request);
    run.success.push_back(r.success);
    run.planning_ms.push_back(r.planning_ms);
    run.length_m.push_back(r.success ? r.length_m : NAN);
    run.clearance_m.push_back(r.success ? r.min_clearance_m : NAN);
    run.collision_checks.push_back(static_cast<double>(r.collision_checks));
  }
  run.memory_bytes = planner->memoryBytes();
  return run;
}

Json plannerReport(const PlannerRun& run, const PlannerRun& reference) {
  Json out = Json::object().set("planner", run.name).set("built", run.built);
  if (!run.built) return out.set("note", run.note);
  std::vector<double> ratios;
  std::size_t solved = 0;
  for (std::size_t i = 0; i < run.success.size(); ++i) {
    solved += run.success[i] ? 1 : 0;
    if (run.success[i] && i < reference.success.size() && reference.success[i]) {
      ratios.push_back(run.length_m[i] / reference.length_m[i]);
    }
  }
  const double pairs = static_cast<double>(run.success.size());
  double checks = 0.0;
  for (double c : run.collision_checks) checks += c;
  return out.set("build_ms", run.build_ms)
      .set("memory_bytes", run.memory_bytes)
      .set("success_rate", pairs > 0 ? static_cast<double>(solved) / pairs : NAN)
      .set("planning_ms_median", quantile(run.planning_ms, 0.5))
      .set("planning_ms_p95", quantile(run.planning_ms, 0.95))
      .set("planning_ms_max", quantile(run.planning_ms, 1.0))
      .set("length_m_median", quantile(run.length_m, 0.5))
      .set("length_ratio_vs_grid_median", quantile(ratios, 0.5))
      .set("length_ratio_vs_grid_p95", quantile(ratios, 0.95))
      .set("length_ratio_vs_grid_max", quantile(ratios, 1.0))
      .set("min_clearance_m_min", quantile(run.clearance_m, 0.0))
      .set("collision_checks_mean", pairs > 0 ? checks / pairs : NAN);
}

}  // namespace strata::bench
