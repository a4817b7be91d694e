#include "cli/repeat_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "cli/option_checks.h"
#include "cli/repeat_plot.h"
#include "cli/repeat_report.h"
#include "cli/run_outputs.h"
#include "cli/teach_command.h"
#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/core/progress.h"
#include "strata/localize/prior_map.h"
#include "strata/sim/sim_setup.h"
#include "strata/store/session_store.h"

namespace strata::apps {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kOutputs = {"report.json", "repeat.png", "*_trajectory.csv",
                                           "*_map.strata"};

/// The teach folder's teach.json, after checking that the folder is a teach of this world.
Json checkTaught(const RepeatOptions& o, const sim::World& world) {
  const fs::path dir(o.taught_dir);
  if (!fs::is_directory(dir)) {
    throw InputError("--taught '" + o.taught_dir + "' is not a folder");
  }
  if (!fs::is_regular_file(dir / repeat::kMapFile)) {
    throw InputError("--taught '" + o.taught_dir + "' holds no " + repeat::kMapFile +
                     ": not a teach folder (write one with `strata teach`)");
  }
  if (!fs::is_regular_file(dir / kTeachJson)) {
    throw InputError("--taught '" + o.taught_dir + "' holds no " + kTeachJson +
                     ": not a teach folder (write one with `strata teach`)");
  }
  Json teach;
  try {
    const std::vector<std::uint8_t> bytes = readFile((dir / kTeachJson).string());
    teach = parseJson(std::string(bytes.begin(), bytes.end()));
  } catch (const nlohmann::json::exception& e) {
    throw InputError("--taught: " + (dir / kTeachJson).string() + " is not valid JSON (" +
                     e.what() + ")");
  }
  if (!teach.contains("world") || !teach["world"].is_string()) {
    throw InputError("--taught: " + (dir / kTeachJson).string() + " names no world");
  }
  const std::string taught_world = teach["world"].get<std::string>();
  if (taught_world != world.name()) {
    throw InputError("--taught '" + o.taught_dir + "' was taught in world '" + taught_world +
                     "', not in '" + world.name() + "' (" + o.world_path + ")");
  }
  if (teach.contains("world_seed") && teach["world_seed"].get<std::uint64_t>() != world.seed()) {
    throw InputError("--taught '" + o.taught_dir + "' was taught in world '" + taught_world +
                     "' with seed " + std::to_string(teach["world_seed"].get<std::uint64_t>()) +
                     ", this world file has seed " + std::to_string(world.seed()));
  }
  return teach;
}

repeat::RepeatConfig repeatConfig(const RepeatOptions& o, const Json& teach) {
  repeat::RepeatConfig c;
  const Json& camera = teach.at("camera");
  c.camera.width_px = camera.at("width_px").get<int>();
  c.camera.height_px = camera.at("height_px").get<int>();
  c.camera.horizontal_fov_rad = camera.at("horizontal_fov_rad").get<double>();
  c.camera.texture = camera.at("texture").get<bool>();
  c.camera.texture_contrast = camera.value("texture_contrast", 0.6);
  c.camera.texture_scale = camera.value("texture_scale", 1.0);
  c.camera_rate_hz = camera.at("rate_hz").get<double>();
  c.seed = o.seed;
  c.localize_every = o.localize_every;
  c.live_map = !o.no_checks;
  c.validate();
  return c;
}

void printRun(const std::string& mode, const repeat::RepeatResult& r) {
  std::printf(
      "%s: %s; following error %.3f m RMS, %.3f m max; flown %.1f m of %.1f m taught; drift "
      "%.3f m final, %.3f m max; localised %zu of %zu (%zu rejected); %zu stops, %zu "
      "collisions; %.0f s simulated, %.0f s wall\n",
      mode.c_str(), r.stop_reason.c_str(), r.following_rms_m, r.following_max_m, r.path_length_m,
      r.taught_length_m, r.drift_final_m, r.drift_max_m, r.localized, r.localizations.size(),
      r.rejected, r.stops.size(), r.collisions.size(), r.sim_time_s, r.wall_s);
}

int runChecked(const RepeatOptions& o) {
  if (o.world_path.empty()) throw InputError("a world file is required");
  if (o.taught_dir.empty()) throw InputError("--taught DIR is required");
  if (o.out_dir.empty()) throw InputError("--out DIR is required");
  requireCount(o.session, "--session", 0, 1000);
  requireCount(o.localize_every, "--localize-every", 1, 100);
  if (o.no_checks && o.save_map) throw InputError("--map needs the live map: drop --no-checks");
  if (o.no_localization && o.compare) {
    throw InputError("--compare runs with and without localisation; drop --no-localization");
  }
  OutputPaths paths;
  paths.inputFile(o.world_path, "the world file");
  outputFolderFiles(paths, o.out_dir, "--out", {"report.json", "repeat.png"});
  paths.check();
  if (!fs::is_regular_file(o.world_path)) {
    throw InputError("world file '" + o.world_path + "' not found");
  }
  const auto world = sim::loadWorld(o.world_path, 0, 0);
  const Json teach = checkTaught(o, *world);
  if (o.session >= world->sessionCount()) {
    throw InputError("--session " + std::to_string(o.session) + ": world '" + world->name() +
                     "' has " + std::to_string(world->sessionCount()) + " sessions");
  }
  repeat::RepeatConfig config = repeatConfig(o, teach);
  const repeat::TaughtPath taught = repeat::TaughtPath::load(o.taught_dir);
  std::vector<std::string> modes;
  if (!o.no_localization) modes.push_back("localization");
  if (o.no_localization || o.compare) modes.push_back("odometry");
  // The teach map: localisation, and what the teach saw for the check of the path ahead.
  std::optional<localize::PriorMap> map;
  {
    store::StoreOptions store_options;
    store_options.read_only = true;
    store::Store db((fs::path(o.taught_dir) / repeat::kMapFile).string(), store_options);
    std::optional<ProgressBar> bar;
    map.emplace(localize::PriorMap::fromStore(db, {}, [&](std::size_t done, std::size_t total) {
      if (!bar) bar.emplace("repeat: loading the teach map", total, !o.quiet);
      bar->update(done);
    }));
    if (bar) bar->finish();
  }
  vk::ContextOptions context_options;
  context_options.device_selector = o.device;
  const auto context = vk::Context::create(context_options);
  OutputCleanup cleanup;
  cleanup.folder(o.out_dir, kOutputs);
  fs::create_directories(o.out_dir);
  Json report;
  report["world"] = world->name();
  report["session"] = o.session;
  report["taught"] = {{"folder", fs::absolute(o.taught_dir).lexically_normal().string()},
                      {"session", teach.value("session", 0)},
                      {"length_m", taught.length_m()}};
  report["runs"] = Json::array();
  std::vector<PlotSeries> series = {{"taught (true)", {90, 90, 90}, taught.p_W, 3}};
  for (const std::string& mode : modes) {
    config.localize_every = mode == "localization" ? o.localize_every : 0;
    config.save_map_path =
        o.save_map ? (fs::path(o.out_dir) / (mode + "_map.strata")).string() : std::string();
    const repeat::RepeatResult r = repeat::runRepeat(
        *world, o.session, taught, map ? &*map : nullptr, config, *context,
        [&](double t, double progress_m, double length_m, const repeat::RepeatResult& so_far) {
          if (o.quiet) return;
          std::fprintf(stderr, "[%s] t=%6.1f s  %5.1f of %.1f m  localised %zu of %zu\n",
                       mode.c_str(), t, progress_m, length_m,
                       static_cast<std::size_t>(std::count_if(
                           so_far.localizations.begin(), so_far.localizations.end(),
                           [](const repeat::LocalizationRecord& l) { return l.localized; })),
                       so_far.localizations.size());
        });
    printRun(mode, r);
    report["runs"].push_back(repeatRunJson(mode, r));
    writeRepeatCsv((fs::path(o.out_dir) / (mode + "_trajectory.csv")).string(), r);
    const bool loc = mode == "localization";
    series.push_back({loc ? "flown (true)" : "flown without localisation (true)",
                      loc ? std::array<int, 3>{30, 110, 220} : std::array<int, 3>{200, 50, 50},
                      r.true_W, 2});
    if (loc || modes.size() == 1) {
      series.push_back({loc ? "estimate" : "estimate (odometry)", {240, 150, 20}, r.estimate_M, 1});
    }
  }
  writeTextAtomically((fs::path(o.out_dir) / "report.json").string(), jsonFileText(report));
  const Json& first = report["runs"][0];
  char caption[200];
  std::snprintf(caption, sizeof(caption),
                "%s session %d, %s: following error %.3f m RMS, %.3f m max", world->name().c_str(),
                o.session, modes[0].c_str(), first["following_error_m"]["rms"].get<double>(),
                first["following_error_m"]["max"].get<double>());
  writeTopDownPng((fs::path(o.out_dir) / "repeat.png").string(), *world, series, {caption});
  cleanup.keep();
  return 0;
}

}  // namespace

CLI::App* addRepeatCommand(CLI::App& app, RepeatOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "repeat", "Teach and repeat: fly a taught path again in a later session, localising");
  cmd->add_option("world", o.world_path, "World file (YAML), the one the path was taught in")
      ->required();
  cmd->add_option("--taught", o.taught_dir, "Teach folder (`strata teach`)")->required();
  cmd->add_option("--session", o.session, "World session to repeat in")->capture_default_str();
  cmd->add_option("--out", o.out_dir, "Output folder")->required();
  cmd->add_flag("--no-localization", o.no_localization, "Odometry alone (no localisation)");
  cmd->add_flag("--compare", o.compare, "Run with and without localisation");
  cmd->add_flag("--no-checks", o.no_checks,
                "No live map and no checks of the path ahead: the taught path flown blind");
  cmd->add_flag("--map", o.save_map, "Save the live map of each run (<mode>_map.strata)");
  cmd->add_option("--seed", o.seed, "Seed of the repeat's odometry drift and depth noise")
      ->capture_default_str();
  cmd->add_option("--localize-every", o.localize_every, "Localise every N-th camera frame")
      ->capture_default_str();
  cmd->add_option("--device", o.device,
                  "Vulkan device index or name substring (env STRATA_DEVICE)");
  cmd->add_flag("--quiet", o.quiet, "No progress lines");
  return cmd;
}

int runRepeatCommand(const RepeatOptions& options) {
  try {
    return runChecked(options);
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata repeat: input error: %s\n", e.what());
    return 2;
  } catch (const DeviceError& e) {
    std::fprintf(stderr, "strata repeat: device error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata repeat: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::apps
