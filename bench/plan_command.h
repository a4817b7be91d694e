#pragma once
// `strata-bench plan`: grid A*, the topological map (and RRT* where built) on the same random,
// reachable start/goal pairs of a shipped world's map: success rate, median and 95th percentile
// planning time, path length against grid A*'s, memory and build time per planner. The targets:
// topo as successful as grid A*, paths within 10 % of its length, median planning time at least
// 100x shorter, its graph's memory against the grid's.
#include <cstdint>
#include <string>

namespace CLI {
class App;
}

namespace strata::bench {

struct PlanBenchOptions {
  std::string world = "office";
  int pairs = 100;
  float radius_m = 0.3f;
  float voxel_size_m = 0.1f;
  float esdf_max_distance_m = 2.0f;
  /// Start and goal at least this far apart (metres): short hops say little about a planner.
  float min_distance_m = 1.0f;
  std::uint64_t seed = 7;
  std::string out_path;    // the JSON report (also printed)
  std::string chart_path;  // "" : <out_path without .json>.png when out_path is set
  std::string map_path;    // also save the map here (.strata) for `strata plan` / `strata topo`
};

CLI::App* addPlanCommand(CLI::App& app, PlanBenchOptions& options);

/// Prints the JSON report; exit code 0, 1 when a target was missed or a self-check failed,
/// 2 bad input.
int runPlanBench(const PlanBenchOptions& options);

}  // namespace strata::bench
