#pragma once
// The measured part of `strata-bench plan`: reachable random pairs, one planner over all of them.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "strata/core/statistics.h"  // quantile
#include "json.h"
#include "strata/plan/collision_checker.h"
#include "strata/plan/traversability.h"

namespace strata::bench {

using PointPair = std::pair<Eigen::Vector3f, Eigen::Vector3f>;

/// `count` pairs of traversable voxel centres in one 6-connected component of `grid`, at least
/// `min_distance_m` apart, drawn uniformly with `seed` (the start over all traversable voxels,
/// the goal over its component). Fewer when the grid offers none.
std::vector<PointPair> reachablePairs(const plan::TraversabilityGrid& grid, float voxel_size_m,
                                      int count, float min_distance_m, std::uint64_t seed);

struct PlannerRun {
  std::string name;
  bool built = false;
  std::string note;  // why it did not run, when not built
  double build_ms = 0.0;
  std::size_t memory_bytes = 0;
  std::vector<bool> success;
  std::vector<double> planning_ms;
  std::vector<double> length_m;
  std::vector<double> clearance_m;
  std::vector<double> collision_checks;
};

/// Builds the planner `name` through the factory and plans every pair.
PlannerRun runPlanner(const std::string& name, const EsdfMap& esdf, float radius_m,
                      const std::vector<PointPair>& pairs);

/// Per-planner summary; ratios against `reference` (grid A*) on the pairs both solved.
Json plannerReport(const PlannerRun& run, const PlannerRun& reference);

}  // namespace strata::bench
