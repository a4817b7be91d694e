#include "cli/explore_command.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>
#include <vector>

#include "cli/explore_outputs.h"
#include "cli/option_checks.h"
#include "cli/run_outputs.h"
#include "strata/sim/sim_setup.h"
#include "strata/core/error.h"
#include "strata/core/output_paths.h"
#include "strata/explore/dead_end.h"
#include "strata/explore/history_planner.h"
#include "strata/explore/nbvp_planner.h"
#include "strata/mesh/ply.h"

namespace strata::apps {
namespace {

namespace fs = std::filesystem;
constexpr float kDefaultStartHeightM = 1.2f;
// The camera's image: ExplorationConfig::validate()'s smallest, and a bound on the largest.
constexpr int kMinCameraPx = 8;
constexpr int kMaxCameraPx = 8192;

/// `count` comma-separated finite numbers, else an InputError naming the option and `expected`.
std::vector<float> parseNumbers(const std::string& text, std::size_t count, const char* option,
                                const char* expected) {
  std::stringstream s(text);
  std::vector<float> v(count);
  for (std::size_t i = 0; i < count; ++i) {
    char comma = ',';
    if (i > 0) s >> comma;
    s >> v[i];
    if (s.fail() || comma != ',' || !std::isfinite(v[i])) break;
    if (i + 1 == count && (s >> std::ws).eof()) return v;
  }
  throw InputError(std::string(option) + ": expected " + expected + ", got '" + text + "'");
}

Eigen::Vector3f parseStart(const std::string& text) {
  const std::vector<float> v = parseNumbers(text, 3, "--start", "X,Y,Z in metres");
  return {v[0], v[1], v[2]};
}

/// --dead-end and --dead-end-mouth as given, checked before any file is read.
struct DeadEndOption {
  Eigen::AlignedBox2f region;
  std::optional<Eigen::Vector2f> mouth;
};

std::optional<DeadEndOption> parseDeadEndOption(const ExploreOptions& o) {
  if (o.dead_end.empty()) {
    if (!o.dead_end_mouth.empty()) throw InputError("--dead-end-mouth needs --dead-end");
    return std::nullopt;
  }
  const char* expected = "X0,Y0,X1,Y1 in metres with X0 < X1 and Y0 < Y1";
  const std::vector<float> v = parseNumbers(o.dead_end, 4, "--dead-end", expected);
  if (!(v[0] < v[2]) || !(v[1] < v[3])) {
    throw InputError(std::string("--dead-end: expected ") + expected + ", got '" + o.dead_end +
                     "'");
  }
  DeadEndOption out{Eigen::AlignedBox2f(Eigen::Vector2f(v[0], v[1]), Eigen::Vector2f(v[2], v[3])),
                    std::nullopt};
  if (!o.dead_end_mouth.empty()) {
    const std::vector<float> m = parseNumbers(o.dead_end_mouth, 2, "--dead-end-mouth", "X,Y");
    out.mouth = Eigen::Vector2f(m[0], m[1]);
  }
  return out;
}

/// The dead end to time, if any: its region and where it opens.
std::optional<explore::DeadEnd> deadEndFor(const std::optional<DeadEndOption>& option,
                                           const Eigen::Vector3f& start_W) {
  if (!option) return std::nullopt;
  if (option->mouth) return explore::DeadEnd{option->region, *option->mouth};
  if (option->region.contains(start_W.head<2>())) {
    throw InputError(
        "--dead-end: the start lies inside the dead end; say where it opens with "
        "--dead-end-mouth X,Y");
  }
  return explore::deadEndSeenFrom(option->region, start_W);
}

explore::ExplorationConfig loopConfig(const ExploreOptions& o) {
  explore::ExplorationConfig c;
  c.time_limit_s = o.time_limit_s;
  if (o.voxel_size_m > 0.0f) c.voxel_size_m = o.voxel_size_m;
  c.camera_width_px = o.camera_width_px;
  c.camera_height_px = o.camera_height_px;
  c.eval_period_s = o.eval_period_s;
  c.seed = o.seed;
  c.validate();
  return c;
}

/// The local tree's sampling box (half extents, metres): `--tree-box`, else the planners' default.
std::optional<Eigen::Vector3f> parseTreeBox(const std::string& text) {
  if (text.empty()) return std::nullopt;
  const std::vector<float> v = parseNumbers(text, 3, "--tree-box", "X,Y,Z half extents > 0 m");
  if (!(v[0] > 0.0f && v[1] > 0.0f && v[2] > 0.0f)) {
    throw InputError("--tree-box: expected X,Y,Z half extents > 0 m, got '" + text + "'");
  }
  return Eigen::Vector3f(v[0], v[1], v[2]);
}

std::unique_ptr<explore::ExplorationPlanner> makePlanner(
    const std::string& name, unsigned long long seed, const std::optional<Eigen::Vector3f>& box) {
  if (name == "history") {
    explore::HistoryConfig c;
    c.seed = seed;
    if (box) c.tree.half_extent_m = *box;
    return std::make_unique<explore::HistoryPlanner>(c);
  }
  explore::NbvpConfig c;
  c.seed = seed;
  if (box) c.tree.half_extent_m = *box;
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
                                  const Eigen::Vector3f& start,
                                  const std::optional<Eigen::Vector3f>& tree_box,
                                  vk::Context& context) {
  const float start_yaw_rad = static_cast<float>(o.start_yaw_deg * M_PI / 180.0);
  explore::ExplorationLoop loop(world, truth, config, {start, start_yaw_rad}, context);
  auto planner = makePlanner(name, o.seed, tree_box);
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
      result.stop_reason.c_str(), result.path_length_m, result.collisions(), times.median_ms,
      times.p95_ms, result.wall_s);
  return result;
}

const std::vector<std::string> kPlannerFiles = {"curve.csv", "steps.csv", "path.png",
                                                "map.strata", "mesh.ply"};

/// Every option, before any file is read: InputError naming the option and what it accepts.
void checkOptions(const ExploreOptions& o) {
  if (o.world_path.empty()) throw InputError("a world file is required");
  if (o.out_dir.empty()) throw InputError("--out DIR is required");
  if (o.planner != "history" && o.planner != "nbvp") {
    throw InputError("--planner: unknown planner '" + o.planner + "' (choose history or nbvp)");
  }
  requireNumber(o.time_limit_s, "--time-limit", "simulated seconds", 0.0, false);
  if (o.voxel_size_m != 0.0f) {
    requireNumberIn(o.voxel_size_m, "--voxel", "metres", 0.001, 1.0);  // MapConfig's range
  }
  requireNumber(o.eval_period_s, "--eval-period", "simulated seconds", 0.0, false);
  if (!std::isfinite(o.start_yaw_deg)) {
    throw InputError("--start-yaw must be a finite angle in degrees, not " +
                     std::to_string(o.start_yaw_deg));
  }
  requireCount(o.camera_width_px, "--width", kMinCameraPx, kMaxCameraPx);
  requireCount(o.camera_height_px, "--height", kMinCameraPx, kMaxCameraPx);
  if (!o.start.empty()) parseStart(o.start);
}

/// The world against the outputs: the folder, its files and each planner's folder.
void checkOutputs(const ExploreOptions& o, const std::vector<std::string>& planners) {
  OutputPaths paths;
  paths.inputFile(o.world_path, "the world file");
  outputFolderFiles(paths, o.out_dir, "--out", {"curve.png", "report.json"});
  for (const std::string& name : planners) {
    outputFolderFiles(paths, (fs::path(o.out_dir) / name).string(), "--out", kPlannerFiles);
  }
  paths.check();
}

int runChecked(const ExploreOptions& o) {
  checkOptions(o);
  explore::ExplorationConfig config = loopConfig(o);
  const std::optional<Eigen::Vector3f> tree_box = parseTreeBox(o.tree_box);
  const std::optional<DeadEndOption> dead_end_option = parseDeadEndOption(o);
  std::vector<std::string> planners = {o.planner};
  if (o.compare) planners = {"history", "nbvp"};
  checkOutputs(o, planners);
  if (!fs::exists(o.world_path)) throw InputError("world file '" + o.world_path + "' not found");
  const auto world = sim::loadWorld(o.world_path, 0, 1);
  if (o.voxel_size_m == 0.0f) config.voxel_size_m = explore::defaultVoxelSize(*world);
  const Eigen::Vector3f start = o.start.empty()
                                    ? explore::defaultStart(*world, kDefaultStartHeightM, config)
                                    : parseStart(o.start);
  const std::optional<explore::DeadEnd> dead_end = deadEndFor(dead_end_option, start);
  const Eigen::AlignedBox3d b = world->bounds();
  const explore::ExplorationTruth truth(*world, {b.min().cast<float>(), b.max().cast<float>()},
                                        start, config.voxel_size_m);
  vk::ContextOptions context_options;
  context_options.device_selector = o.device;
  const auto context = vk::Context::create(context_options);
  // A failed run (a planner, the device, a write) leaves none of its files, nor the folders it
  // made.
  OutputCleanup cleanup;
  std::vector<std::string> names = {"curve.png", "report.json"};
  names.insert(names.end(), planners.begin(), planners.end());
  cleanup.folder(o.out_dir, names);
  for (const std::string& name : planners) {
    cleanup.folder((fs::path(o.out_dir) / name).string(), kPlannerFiles);
  }
  fs::create_directories(o.out_dir);
  std::vector<explore::ExplorationResult> results;
  for (const std::string& name : planners) {
    results.push_back(runOne(name, o, *world, truth, config, start, tree_box, *context));
  }
  writeExploreCurvePng((fs::path(o.out_dir) / "curve.png").string(), world->name(), results);
  writeExploreReport((fs::path(o.out_dir) / "report.json").string(), world->name(), results, config,
                     start, o.seed, dead_end);
  cleanup.keep();
  return 0;
}

}  // namespace

CLI::App* addExploreCommand(CLI::App& app, ExploreOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "explore", "Closed-loop exploration of a simulated world (history-aware planner or NBVP)");
  cmd->add_option("world", o.world_path, "World file (YAML)")->required();
  cmd->add_option("--planner", o.planner, "history or nbvp")
      ->capture_default_str()
      ->check(CLI::IsMember({"history", "nbvp"}));
  cmd->add_flag("--compare", o.compare, "Run both planners (same world, start and seed)");
  cmd->add_option("--seed", o.seed, "Seed of the planners' sampling and the camera noise")
      ->capture_default_str();
  cmd->add_option("--time-limit", o.time_limit_s, "Simulated seconds per run (> 0)")
      ->capture_default_str()
      ->check(finiteNumber());
  cmd->add_option("--voxel", o.voxel_size_m,
                  "Voxel size of the map and the truth, metres (> 0); default 0.05 for worlds "
                  "whose bounds hold at most 4M such voxels, else 0.1")
      ->check(finiteNumber());
  cmd->add_option("--start", o.start,
                  "Start X,Y,Z (metres); default: nearest the first room's centre at 1.2 m with "
                  "room for the start clearing");
  cmd->add_option("--start-yaw", o.start_yaw_deg,
                  "Heading at the start, degrees about world z from +x")
      ->capture_default_str()
      ->check(finiteNumber());
  cmd->add_option("--dead-end", o.dead_end,
                  "X0,Y0,X1,Y1: a dead end from above (metres); report.json then times how long "
                  "each planner took to leave it");
  cmd->add_option("--dead-end-mouth", o.dead_end_mouth,
                  "X,Y: where the dead end opens (metres); default: its point nearest the start");
  cmd->add_option("--tree-box", o.tree_box,
                  "X,Y,Z: half extents of the local tree's sampling box around the robot, metres "
                  "(default 4,4,0.6)");
  cmd->add_option("--width", o.camera_width_px, "Camera width, px")
      ->capture_default_str()
      ->check(CLI::Range(kMinCameraPx, kMaxCameraPx));
  cmd->add_option("--height", o.camera_height_px, "Camera height, px")
      ->capture_default_str()
      ->check(CLI::Range(kMinCameraPx, kMaxCameraPx));
  cmd->add_option("--eval-period", o.eval_period_s,
                  "Simulated seconds between evaluations of the explored share (> 0)")
      ->capture_default_str()
      ->check(finiteNumber());
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
