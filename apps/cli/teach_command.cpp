#include "cli/teach_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "cli/option_checks.h"
#include "cli/repeat_plot.h"
#include "cli/report_json.h"
#include "cli/run_outputs.h"
#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/core/progress.h"
#include "strata/repeat/teach_recording.h"
#include "strata/sim/sim_setup.h"

namespace strata::apps {
namespace {

namespace fs = std::filesystem;

void checkOptions(const TeachOptions& o) {
  if (o.world_path.empty()) throw InputError("a world file is required");
  if (o.out_dir.empty()) throw InputError("--out DIR is required");
  requireCount(o.session, "--session", 0, 1000);
  requireNumberIn(o.length_m, "--length", "metres", 1.0, 10000.0);
  requireCount(o.width_px, "--width", 32, 4096);
  requireCount(o.height_px, "--height", 24, 4096);
  std::error_code error;
  if (fs::exists(o.out_dir, error) &&
      (!fs::is_directory(o.out_dir, error) || !fs::is_empty(o.out_dir, error))) {
    throw InputError("--out '" + o.out_dir +
                     "' exists and is not an empty folder: a teach writes a folder of its own");
  }
}

repeat::TeachConfig teachConfig(const TeachOptions& o) {
  repeat::TeachConfig c;
  c.route.min_length_m = o.length_m;
  c.camera.width_px = o.width_px;
  c.camera.height_px = o.height_px;
  c.camera.texture = !o.flat;
  c.session = o.session;
  c.seed = o.seed;
  c.validate();
  return c;
}

Json teachJson(const TeachOptions& o, const sim::World& world, const repeat::TeachConfig& c,
               const repeat::TeachResult& r) {
  Json j;
  j["world"] = world.name();
  j["world_file"] = fs::absolute(o.world_path).lexically_normal().string();
  j["world_seed"] = world.seed();
  j["session"] = c.session;
  j["seed"] = c.seed;
  j["frames"] = r.truth.size();
  j["length_m"] = r.length_m;
  j["duration_s"] = r.duration_s;
  j["camera"] = {{"width_px", c.camera.width_px},
                 {"height_px", c.camera.height_px},
                 {"horizontal_fov_rad", c.camera.horizontal_fov_rad},
                 {"texture", c.camera.texture},
                 {"texture_contrast", c.camera.texture_contrast},
                 {"texture_scale", c.camera.texture_scale},
                 {"rate_hz", c.camera_rate_hz}};
  j["drift"] = {
      {"translation_sigma_m_per_sqrt_m", c.drift.translation_sigma_m_per_sqrt_m},
      {"yaw_sigma_rad_per_sqrt_m", c.drift.yaw_sigma_rad_per_sqrt_m},
      {"final_m", r.final_drift_m},
      {"max_m", r.max_drift_m},
      {"final_percent_of_distance", r.length_m > 0.0 ? 100.0 * r.final_drift_m / r.length_m : 0.0}};
  j["map"] = {{"file", repeat::kMapFile},
              {"session", r.import.name},
              {"keyframes", r.import.keyframes},
              {"frame", "the teach's odometry (no true pose in the map)"}};
  j["taught_path"] = repeat::kTaughtPathFile;
  return j;
}

int runChecked(const TeachOptions& o) {
  checkOptions(o);
  const repeat::TeachConfig config = teachConfig(o);
  if (!fs::is_regular_file(o.world_path)) {
    throw InputError("world file '" + o.world_path + "' not found");
  }
  const auto world = sim::loadWorld(o.world_path, 0, 0);
  if (o.session >= world->sessionCount()) {
    throw InputError("--session " + std::to_string(o.session) + ": world '" + world->name() +
                     "' has " + std::to_string(world->sessionCount()) + " sessions");
  }
  OutputCleanup cleanup;
  cleanup.folder(o.out_dir, {"*"});
  std::optional<ProgressBar> bar;
  const repeat::TeachResult r =
      repeat::recordTeach(*world, config, o.out_dir, [&](std::size_t done, std::size_t total) {
        if (!bar) bar.emplace("teach: rendering", total, !o.quiet);
        bar->update(done);
      });
  if (bar) bar->finish();
  writeTextAtomically((fs::path(o.out_dir) / kTeachJson).string(),
                      jsonFileText(teachJson(o, *world, config, r)));
  std::vector<Eigen::Vector3f> truth, odometry;
  for (const tum::TimedPose& p : r.truth) truth.push_back(p.T_W_C.translation().cast<float>());
  for (const tum::TimedPose& p : r.odometry) {
    odometry.push_back(p.T_W_C.translation().cast<float>());
  }
  char line[120], drift[160];
  std::snprintf(line, sizeof(line), "%s session %d: taught path %.1f m, %zu frames",
                world->name().c_str(), o.session, r.length_m, r.truth.size());
  std::snprintf(drift, sizeof(drift),
                "odometry drift %.2f m at the end (%.1f %% of the distance), %.2f m max (%.1f %%)",
                r.final_drift_m, r.length_m > 0 ? 100.0 * r.final_drift_m / r.length_m : 0.0,
                r.max_drift_m, r.length_m > 0 ? 100.0 * r.max_drift_m / r.length_m : 0.0);
  writeTopDownPng((fs::path(o.out_dir) / "teach.png").string(), *world,
                  {{"taught path (true)", {90, 90, 90}, truth, 2},
                   {"taught path as the map holds it (odometry)", {230, 120, 20}, odometry, 2}},
                  {line, drift});
  std::printf("%s; %s\nWrote %s (map %s: %zu keyframes)\n", line, drift, o.out_dir.c_str(),
              repeat::kMapFile, r.import.keyframes);
  cleanup.keep();
  return 0;
}

}  // namespace

CLI::App* addTeachCommand(CLI::App& app, TeachOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "teach", "Teach and repeat: fly and record a taught path through a simulated world");
  cmd->add_option("world", o.world_path, "World file (YAML)")->required();
  cmd->add_option("--out", o.out_dir, "Teach folder to write (new or empty)")->required();
  cmd->add_option("--session", o.session, "World session flown")->capture_default_str();
  cmd->add_option("--seed", o.seed, "Seed of the depth noise and the odometry drift")
      ->capture_default_str();
  cmd->add_option("--length", o.length_m,
                  "Least route length (metres): session 0's path flown forth and back")
      ->capture_default_str()
      ->check(finiteNumber());
  cmd->add_option("--width", o.width_px, "Camera width, px")->capture_default_str();
  cmd->add_option("--height", o.height_px, "Camera height, px")->capture_default_str();
  cmd->add_flag("--flat", o.flat, "Flat-shaded colour (default: the world texture)");
  cmd->add_flag("--quiet", o.quiet, "No progress bar");
  return cmd;
}

int runTeach(const TeachOptions& options) {
  try {
    return runChecked(options);
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata teach: input error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata teach: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::apps
