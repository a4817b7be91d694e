#include "cli/explore_command.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <optional>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "cli/explore_outputs.h"
#include "cli/sim_setup.h"
#include "core/error.h"
#include "explore/history_planner.h"
#include "explore/nbvp_planner.h"
#include "mesh/ply.h"

namespace strata::apps {
namespace {

namespace fs = std::filesystem;
constexpr float kDefaultStartHeightM = 1.2f;

Eigen::Vector3f parseStart(const std::string& text) {
  std::stringstream s(text);
  Eigen::Vector3f p;
  char comma1 = 0, comma2 = 0;
  s >> p.x() >> comma1 >> p.y() >> comma2 >> p.z();
  if (s.fail() || comma1 != ',' || comma2 != ',' || !(s >> std::ws).eof() || !p.allFinite()) {
    throw InputError("--start: expected X,Y,Z in metres, got '" + text + "'");
  }
  return p;
}

std::optional<Eigen::AlignedBox2f> parseDeadEnd(const std::string& text) {
  if (text.empty()) return std::nullopt;
  std::stringstream s(text);
  float v[4];
  char comma[3] = {0, 0, 0};
  s >> v[0] >> comma[0] >> v[1] >> comma[1] >> v[2] >> comma[2] >> v[3];
  const bool finite = std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]) &&
                      std::isfinite(v[3]);
  if (s.fail() || comma[0] != ',' || comma[1] != ',' || comma[2] != ',' ||
      !(s >> std::ws).eof() || !finite || !(v[0] < v[2]) || !(v[1] < v[3])) {
    throw InputError("--dead-end: expected X0,Y0,X1,Y1 in metres with X0 < X1 and Y0 < Y1, got '" +
                     text + "'");
  }
  return Eigen::AlignedBox2f(Eigen::Vector2f(v[0], v[1]), Eigen::Vector2f(v[2], v[3]));
}

explore::ExplorationConfig loopConfig(const ExploreOptions& o) {
  explore::ExplorationConfig c;
  c.time_limit_s = o.time_limit_s;
  c.voxel_size_m = o.voxel_size_m;
  c.camera_width_px = o.camera_width_px;
  c.camera_height_px = o.camera_height_px;
  c.eval_period_s = o.eval_period_s;
  c.seed = o.seed;
  c.validate();
  return c;
}

std::unique_ptr<explore::ExplorationPlanner> makePlanner(const std::string& name,
                                                         unsigned long long seed) {
  if (name == "history") {
    explore::HistoryConfig c;
    c.seed = seed;
    return std::make_unique<explore::HistoryPlanner>(c);
  }
  explore::NbvpConfig c;
  c.seed = seed;
  return std::make_unique<explore::NbvpPlanner>(c);
}

void printProgress(const std::string& planner, const explore::CurvePoint& point,
                   const explore::StepRecord* last) {
  std::fprintf(stderr, "[%s] t=%6.1f s  explored %5.1f %%  path %6.1f m  step %6.1f ms%s%s\n",
               planner.c_str(), point.sim_time_s, 100.0 * point.explored_fraction,
               point.path_length_m, point.compute_ms, last ? "  " : "",
               last ? last->mode.c_str() : "");
}

/// Runs one planner and writes its folder.
explore::ExplorationResult runOne(const std::string& name, const ExploreOptions& o,
                                  const sim::World& world, const explore::ExplorationTruth& truth,
                                  const explore::ExplorationConfig& config,
                                  const Eigen::Vector3f& start, vk::Context& context) {
  explore::ExplorationLoop loop(world, truth, config, {start, 0.0f}, context);
  auto planner = makePlanner(name, o.seed);
  explore::ExplorationResult result =
      loop.run(*planner, [&](const explore::CurvePoint& p, const explore::StepRecord* last) {
        if (!o.quiet) printProgress(name, p, last);
      });
  const fs::path dir = fs::path(o.out_dir) / name;
  fs::create_directories(dir);
  writeExploreCurveCsv((dir / "curve.csv").string(), result);
  writeExploreStepsCsv((dir / "steps.csv").string(), result);
  Mapper& mapper = loop.mapper();
  mapper.updateEsdf();
  writeExplorePathPng((dir / "path.png").string(), mapper.esdf(), result, start.z());
  mapper.save((dir / "map.strata").string());
  writePly((dir / "mesh.ply").string(), mapper.mesh());
  const StepTimes times = stepTimes(result);
  std::printf(
      "%s: explored %.1f %% of %zu reachable voxels in %.0f s simulated (%s), path %.1f m, "
      "%d collisions, step %.1f ms median / %.1f ms p95, %.1f s wall\n",
      name.c_str(), 100.0 * result.explored_fraction, result.reachable_voxels, result.sim_time_s,
      result.stop_reason.c_str(), result.path_length_m, result.collisions, times.median_ms,
      times.p95_ms, result.wall_s);
  return result;
}

int runChecked(const ExploreOptions& o) {
  if (o.world_path.empty()) throw InputError("a world file is required");
  if (!fs::exists(o.world_path)) throw InputError("world file '" + o.world_path + "' not found");
  if (o.out_dir.empty()) throw InputError("--out DIR is required");
  if (o.planner != "history" && o.planner != "nbvp") {
    throw InputError("--planner must be history or nbvp, got '" + o.planner + "'");
  }
  const explore::ExplorationConfig config = loopConfig(o);
  const std::optional<Eigen::AlignedBox2f> dead_end = parseDeadEnd(o.dead_end);
  const auto world = loadWorld(o.world_path, 0, 1);
  const Eigen::Vector3f start = o.start.empty()
                                    ? explore::defaultStart(*world, kDefaultStartHeightM, config)
                                    : parseStart(o.start);
  const Eigen::AlignedBox3d b = world->bounds();
  const explore::ExplorationTruth truth(*world, {b.min().cast<float>(), b.max().cast<float>()},
                                        start, o.voxel_size_m);
  vk::ContextOptions context_options;
  context_options.device_selector = o.device;
  const auto context = vk::Context::create(context_options);
  fs::create_directories(o.out_dir);
  std::vector<std::string> planners = {o.planner};
  if (o.compare) planners = {"history", "nbvp"};
  std::vector<explore::ExplorationResult> results;
  for (const std::string& name : planners) {
    results.push_back(runOne(name, o, *world, truth, config, start, *context));
  }
  writeExploreCurvePng((fs::path(o.out_dir) / "curve.png").string(), world->name(), results);
  writeExploreReport((fs::path(o.out_dir) / "report.json").string(), world->name(), results, config,
                     start, o.seed, dead_end);
  return 0;
}

}  // namespace

CLI::App* addExploreCommand(CLI::App& app, ExploreOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "explore", "Closed-loop exploration of a simulated world (history-aware planner or NBVP)");
  cmd->add_option("world", o.world_path, "World file (YAML)")->required();
  cmd->add_option("--planner", o.planner, "history or nbvp")->capture_default_str();
  cmd->add_flag("--compare", o.compare, "Run both planners (same world, start and seed)");
  cmd->add_option("--seed", o.seed, "Seed of the planners' sampling and the camera noise")
      ->capture_default_str();
  cmd->add_option("--time-limit", o.time_limit_s, "Simulated seconds per run")
      ->capture_default_str();
  cmd->add_option("--voxel", o.voxel_size_m, "Voxel size of the map and the truth, metres")
      ->capture_default_str();
  cmd->add_option("--start", o.start,
                  "Start X,Y,Z (metres); default: nearest the first room's centre at 1.2 m with "
                  "room for the start clearing");
  cmd->add_option("--dead-end", o.dead_end,
                  "X0,Y0,X1,Y1: a dead end from above (metres); report.json then times how long "
                  "each planner took to leave it (worlds/deadend.yaml: 10.1,3,32.1,5)");
  cmd->add_option("--width", o.camera_width_px, "Camera width, px")->capture_default_str();
  cmd->add_option("--height", o.camera_height_px, "Camera height, px")->capture_default_str();
  cmd->add_option("--eval-period", o.eval_period_s,
                  "Simulated seconds between evaluations of the explored share")
      ->capture_default_str();
  cmd->add_option("--out", o.out_dir, "Output folder")->required();
  cmd->add_option("--device", o.device,
                  "Vulkan device index or name substring (env STRATA_DEVICE)");
  cmd->add_flag("--quiet", o.quiet, "No progress lines");
  return cmd;
}

int runExplore(const ExploreOptions& options) {
  try {
    return runChecked(options);
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata explore: input error: %s\n", e.what());
    return 2;
  } catch (const DeviceError& e) {
    std::fprintf(stderr, "strata explore: device error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata explore: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::apps
