#include "cli/plan_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <vector>

#include "cli/option_checks.h"
#include "cli/plan_load.h"
#include "cli/plan_outputs.h"
#include "cli/run_outputs.h"
#include "strata/core/error.h"
#include "strata/plan/collision_checker.h"
#include "strata/plan/planner_factory.h"

namespace strata::apps {
namespace {

const char* const kPlanners[] = {"grid", "topo", "rrt"};
const std::vector<std::string> kPlanFiles = {"path.csv", "report.json", "path.png"};

/// The options, checked before any file is read: InputError naming the option and what it accepts.
PlanReport checkedRequest(const PlanOptions& o) {
  if (o.map_path.empty()) throw InputError("a map file (.strata) is required");
  if (o.out_dir.empty()) throw InputError("--out DIR is required");
  if (std::find(std::begin(kPlanners), std::end(kPlanners), o.planner) == std::end(kPlanners)) {
    throw InputError("--planner: unknown planner '" + o.planner + "' (choose grid, topo or rrt)");
  }
  PlanReport report;
  report.planner = o.planner;
  report.request.start_W = parsePoint("--from", o.from);
  report.request.goal_W = parsePoint("--to", o.to);
  report.request.radius_m = o.radius_m;
  report.request.unknown = parseUnknownPolicy(o.unknown);
  checkRadius(o.radius_m, o.esdf_max_distance_m);
  return report;
}

int runChecked(const PlanOptions& o) {
  PlanReport report = checkedRequest(o);
  checkMapOutputs(o.map_path, o.out_dir, kPlanFiles);
  const LoadedEsdf loaded = loadEsdf(o.map_path, o.esdf_max_distance_m, o.device);
  const EsdfMap& esdf = *loaded.esdf;
  plan::HostCollisionChecker checker(esdf);
  // Endpoints first: a bad one is bad input, whichever planner runs.
  for (const auto& [what, p] : {std::pair{"start (--from)", report.request.start_W},
                                std::pair{"goal (--to)", report.request.goal_W}}) {
    const std::string problem =
        plan::endpointProblem(esdf, checker, what, p, o.radius_m, report.request.unknown);
    if (!problem.empty()) throw InputError(problem);
  }
  const std::unique_ptr<plan::Planner> planner = plan::makePlanner(
      o.planner, esdf, checker, plan::PlannerOptions{o.radius_m, report.request.unknown});
  report.build_ms = plan::plannerBuildMs(*planner);
  report.result = planner->plan(report.request);
  report.memory_bytes = planner->memoryBytes();
  // A failed write leaves none of the files (nor the folder when this run made it).
  OutputCleanup cleanup;
  cleanup.folder(o.out_dir, kPlanFiles);
  std::filesystem::create_directories(o.out_dir);
  const std::filesystem::path dir(o.out_dir);
  writePathCsv((dir / "path.csv").string(), report.result.path_W);
  writePlanReport((dir / "report.json").string(), report);
  writePathPng((dir / "path.png").string(), esdf, report);
  cleanup.keep();
  const plan::PlanResult& r = report.result;
  if (r.success) {
    std::printf(
        "strata plan: %s path of %.2f m through %zu waypoints, clearance %.2f m, %.2f ms to plan "
        "(%.1f ms to build, %.1f MB); ESDF %.0f ms. Wrote %s/{path.csv,report.json,path.png}.\n",
        o.planner.c_str(), r.length_m, r.path_W.size(), r.min_clearance_m, r.planning_ms,
        report.build_ms, report.memory_bytes / 1e6, loaded.esdf_ms, o.out_dir.c_str());
    return 0;
  }
  std::fprintf(stderr, "strata plan: no path (%s): %s. Wrote %s/report.json.\n", o.planner.c_str(),
               r.message.c_str(), o.out_dir.c_str());
  return 1;
}

}  // namespace

CLI::App* addPlanCommand(CLI::App& app, PlanOptions& o) {
  CLI::App* cmd = app.add_subcommand("plan", "Plan a path for a spherical robot on a saved map");
  cmd->add_option("map", o.map_path, "Map file (.strata)")->required();
  cmd->add_option("--from", o.from, "Start x,y,z (metres, world frame)")->required();
  cmd->add_option("--to", o.to, "Goal x,y,z (metres, world frame)")->required();
  cmd->add_option("--planner", o.planner, "grid (A*), topo (topological map) or rrt (RRT*)")
      ->capture_default_str()
      ->check(CLI::IsMember({"grid", "topo", "rrt"}));
  cmd->add_option("--radius", o.radius_m, "Robot radius, metres (>= 0)")
      ->capture_default_str()
      ->check(finiteNumber());
  cmd->add_option("--unknown", o.unknown, "Unknown space: occupied (safe) or free")
      ->capture_default_str()
      ->check(CLI::IsMember({"occupied", "free"}));
  cmd->add_option("--esdf-max-distance", o.esdf_max_distance_m,
                  "ESDF maximum distance, metres (above the radius)")
      ->capture_default_str()
      ->check(finiteNumber());
  cmd->add_option("--out", o.out_dir, "Output folder")->required();
  cmd->add_option("--device", o.device,
                  "Vulkan device index or name substring (env STRATA_DEVICE)");
  return cmd;
}

int runPlan(const PlanOptions& options) {
  try {
    return runChecked(options);
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata plan: input error: %s\n", e.what());
    return 2;
  } catch (const DeviceError& e) {
    std::fprintf(stderr, "strata plan: device error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata plan: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::apps
