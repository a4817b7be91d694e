#include "plan_command.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>

#include "chart.h"
#include "strata/core/error.h"
#include "json.h"
#include "machine_info.h"
#include "strata/map/map_file.h"
#include "strata/plan/grid_astar.h"
#include "plan_runs.h"
#include "plan_update.h"
#include "plan_world_map.h"

namespace strata::bench {
namespace {

// The targets of the topological map against grid A* (docs/plan.md).
constexpr double kMaxLengthRatio = 1.10;
constexpr double kMinSpeedup = 100.0;

/// The middle of the map's allocated bounds in x and y, at 1.5 m: the top of the benchmark's
/// obstacle (which reaches down through the floor).
Eigen::Vector3d worldCentre(const EsdfMap& esdf) {
  const plan::VoxelBox b = plan::allocatedBounds(esdf);
  const Eigen::Vector3d lo = b.lo.cast<double>() * esdf.voxel_size_m;
  const Eigen::Vector3d hi = (b.hi + Eigen::Vector3i::Ones()).cast<double>() * esdf.voxel_size_m;
  return Eigen::Vector3d(0.5 * (lo.x() + hi.x()), 0.5 * (lo.y() + hi.y()), 1.5);
}

Json settingsJson(const PlanBenchOptions& o) {
  return Json::object()
      .set("world", o.world)
      .set("pairs", o.pairs)
      .set("radius_m", static_cast<double>(o.radius_m))
      .set("voxel_size_m", static_cast<double>(o.voxel_size_m))
      .set("esdf_max_distance_m", static_cast<double>(o.esdf_max_distance_m))
      .set("min_pair_distance_m", static_cast<double>(o.min_distance_m))
      .set("unknown", "occupied")
      .set("seed", o.seed);
}

Json planNotes() {
  return Json::array()
      .push(
          "map: the world's session 0 as a TSDF of the exact signed distance (observed "
          "wherever in front of or within the truncation band) and its exact ESDF "
          "(computeEsdfReference); see bench/plan_world_map.h")
      .push(
          "pairs: traversable voxel centres in one 6-connected component of the traversable "
          "grid (the robot sphere free), at least min_pair_distance_m apart, seeded")
      .push(
          "planning_ms: the query only (steady_clock), on the host ESDF copy, one thread "
          "for the search; build_ms: the planner's structures (grid, clusters and portals)")
      .push(
          "length ratio: a planner's path length over grid A*'s on the pairs both solved; "
          "grid A*'s path is pruned and relaxed with the capsule test")
      .push(
          "memory: grid A* keeps 1 byte per cell of the map's bounds plus 20 bytes of search "
          "state per cell; the topological map keeps boxes, portals, portal lists, landmark "
          "distances and a block lookup");
}

/// Median planning time of each planner that ran, and its 95th percentile.
void writeChart(const std::string& path, const std::vector<PlannerRun>& runs) {
  BarChart chart;
  chart.title = "Planning time per query (ms)";
  chart.y_label = "ms";
  chart.series = {{"median", {70, 110, 200}}, {"95th percentile", {230, 140, 50}}};
  for (const PlannerRun& run : runs) {
    if (!run.built) continue;
    ChartGroup group;
    group.label = run.name;
    const double median = quantile(run.planning_ms, 0.5), p95 = quantile(run.planning_ms, 0.95);
    group.bars.push_back({"median", {median}, {0}, formatTick(median)});
    group.bars.push_back({"p95", {p95}, {1}, formatTick(p95)});
    chart.groups.push_back(group);
  }
  writeChartPng(drawBarChart(chart), path);
}

int runChecked(const PlanBenchOptions& o) {
  if (o.pairs < 1) throw InputError("--pairs must be at least 1");
  if (!(o.radius_m >= 0.0f) || !(o.radius_m < o.esdf_max_distance_m)) {
    throw InputError("--radius must be >= 0 and below the ESDF max distance");
  }
  std::fprintf(stderr, "strata-bench plan: building the map of '%s' at %.2f m...\n",
               o.world.c_str(), static_cast<double>(o.voxel_size_m));
  const WorldMap map = buildWorldMap(o.world, o.voxel_size_m, o.esdf_max_distance_m);
  if (!o.map_path.empty()) saveMap(map.tsdf, o.map_path);
  plan::HostCollisionChecker checker(map.esdf);
  plan::GridAStarPlanner pair_grid(map.esdf, checker);
  const std::vector<PointPair> pairs =
      reachablePairs(pair_grid.prepare(o.radius_m, UnknownPolicy::kOccupied), o.voxel_size_m,
                     o.pairs, o.min_distance_m, o.seed);
  if (pairs.empty()) throw InputError("the map of '" + o.world + "' has no reachable pair");
  std::vector<PlannerRun> runs;
  for (const char* name : {"grid", "topo", "rrt"}) {
    std::fprintf(stderr, "strata-bench plan: %s on %zu pairs...\n", name, pairs.size());
    runs.push_back(runPlanner(name, map.esdf, o.radius_m, pairs));
  }
  const PlannerRun& grid = runs[0];
  const PlannerRun& topo = runs[1];
  Json planners = Json::array();
  for (const PlannerRun& run : runs) planners.push(plannerReport(run, grid));
  std::size_t disagreements = 0;
  std::vector<double> ratios;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    disagreements += grid.success[i] != topo.success[i] ? 1 : 0;
    if (grid.success[i] && topo.success[i]) ratios.push_back(topo.length_m[i] / grid.length_m[i]);
  }
  const double speedup = quantile(grid.planning_ms, 0.5) / quantile(topo.planning_ms, 0.5);
  const double ratio_p95 = quantile(ratios, 0.95);
  Json targets =
      Json::object()
          .set("same_success_as_grid", disagreements == 0)
          .set("success_disagreements", disagreements)
          .set("length_within_10_percent_median", quantile(ratios, 0.5) <= kMaxLengthRatio)
          .set("length_within_10_percent_p95", ratio_p95 <= kMaxLengthRatio)
          .set("pairs_over_10_percent",
               static_cast<std::int64_t>(std::count_if(
                   ratios.begin(), ratios.end(), [](double r) { return r > kMaxLengthRatio; })))
          .set("median_speedup_vs_grid", speedup)
          .set("speedup_at_least_100x", speedup >= kMinSpeedup)
          .set("topo_memory_over_grid_memory",
               static_cast<double>(topo.memory_bytes) / static_cast<double>(grid.memory_bytes));
  // A box 0.6 x 0.6 x 1.5 m standing 2.5 m left of the map's middle (in the office's corridor,
  // clear of its pillar).
  const Eigen::Vector3d centre = worldCentre(map.esdf) - Eigen::Vector3d(2.5, 0.0, 0.0);
  const Eigen::AlignedBox3d obstacle(centre - Eigen::Vector3d(0.3, 0.3, 10.0),
                                     centre + Eigen::Vector3d(0.3, 0.3, 0.0));
  bool update_ok = true;
  std::fprintf(stderr, "strata-bench plan: topological map update after a change...\n");
  const Json update = measureTopoUpdate(map, obstacle, plan::TopoOptions{o.radius_m}, &update_ok);
  Json report = Json::object()
                    .set("benchmark", "plan")
                    .set("machine", machineInfo("host (no device)", ""))
                    .set("settings", settingsJson(o))
                    .set("map", Json::object()
                                    .set("blocks", map.tsdf.blockCount())
                                    .set("voxels", map.tsdf.blockCount() * kVoxelsPerBlock)
                                    .set("truth_tsdf_ms", map.tsdf_ms)
                                    .set("esdf_reference_ms", map.esdf_ms)
                                    .set("traversable_voxels", pair_grid.buildStats().traversable))
                    .set("pairs", pairs.size())
                    .set("planners", planners)
                    .set("topo_vs_grid", targets)
                    .set("topo_update", update)
                    .set("notes", planNotes());
  emitReport(report, o.out_path);
  std::string chart = o.chart_path;
  if (chart.empty() && !o.out_path.empty()) {
    chart = o.out_path.substr(0, o.out_path.rfind('.')) + ".png";
  }
  if (!chart.empty()) writeChart(chart, runs);
  return disagreements == 0 && update_ok ? 0 : 1;
}

}  // namespace

CLI::App* addPlanCommand(CLI::App& app, PlanBenchOptions& o) {
  CLI::App* cmd = app.add_subcommand("plan", "Grid A*, topological map (and RRT*) on random pairs");
  cmd->add_option("--world", o.world, "Shipped world name or world file")->capture_default_str();
  cmd->add_option("--pairs", o.pairs, "Random reachable start/goal pairs")->capture_default_str();
  cmd->add_option("--radius", o.radius_m, "Robot radius, metres")->capture_default_str();
  cmd->add_option("--voxel", o.voxel_size_m, "Voxel size, metres")->capture_default_str();
  cmd->add_option("--esdf-max-distance", o.esdf_max_distance_m, "ESDF max distance, metres")
      ->capture_default_str();
  cmd->add_option("--min-distance", o.min_distance_m, "Least start-goal distance, metres")
      ->capture_default_str();
  cmd->add_option("--seed", o.seed, "Seed of the pairs")->capture_default_str();
  cmd->add_option("--out", o.out_path, "Also write the JSON report here");
  cmd->add_option("--chart", o.chart_path, "Bar chart PNG (default: beside --out)");
  cmd->add_option("--save-map", o.map_path, "Also save the map (.strata) for strata plan/topo");
  return cmd;
}

int runPlanBench(const PlanBenchOptions& options) {
  try {
    return runChecked(options);
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata-bench plan: input error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata-bench plan: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::bench
