#include "diff_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>

#include "strata/core/error.h"
#include "diff_runs.h"
#include "machine_info.h"
#include "strata/sim/world/world_paths.h"

namespace strata::bench {
namespace {

Json diffNotes() {
  return Json::array()
      .push(
          "device times come from Vulkan timestamp queries around each stage of "
          "ChangeDetector::endSession (ChangeUpdateStats); reference times from "
          "std::chrono::steady_clock around the same stages of the C++ reference (2 threads)")
      .push(
          "the reference runs on the device's own session maps (ChangeDetector::addSessionMap), "
          "so both compute the same labels; label_agreement is the share of voxels with the same "
          "label where either is known (target: >= 0.999)")
      .push(
          "a session update: neighbour table, difference, erosion, dilation (D), static update "
          "(S), and the session's dynamic part (difference against the new S, erosion, "
          "dilation); every pass runs over all allocated blocks; per-voxel figures divide by "
          "blocks * 512")
      .push(
          "kernels are compiled before the first update (DeviceChange warms them up), so session "
          "0 is timed like the others; it does the same work on an empty S")
      .push(
          "on lavapipe the device is this CPU: device time is CPU time on LP_NUM_THREADS threads, "
          "and timings are noisy when other work shares the cores (see load_average)");
}

Json settingsJson(const DiffBenchOptions& o, const DiffRunSettings& s) {
  const change::ChangeConfig& c = s.change;
  return Json::object()
      .set("world", o.world)
      .set("sessions", s.sessions)
      .set("frames_per_session", o.frames > 0 ? Json(o.frames) : Json("all (30 Hz)"))
      .set("voxel_size_m", static_cast<double>(s.map.voxel_size_m))
      .set("truncation_m", static_cast<double>(s.map.truncationDistance()))
      .set("allocate_free_space", s.map.allocate_free_space)
      .set("map_config", s.map.describe())
      .set("change_config",
           Json::object()
               .set("min_weight", static_cast<double>(c.min_weight))
               .set("difference_threshold_m", static_cast<double>(c.difference_threshold_m))
               .set("erosion_kernel_voxels", c.erosion_kernel_voxels)
               .set("dilation_kernel_voxels", c.dilation_kernel_voxels)
               .set("merge_close_m", static_cast<double>(c.merge_close_m)))
      .set("reference", s.reference)
      .set("notes", diffNotes());
}

DiffRunSettings makeSettings(const DiffBenchOptions& o) {
  DiffRunSettings s;
  s.map.voxel_size_m = o.voxel_size_m;
  s.map.allocate_free_space = o.free_space;
  s.map.validate();
  s.change.validate(o.voxel_size_m);  // defaults: the method's (5 cm threshold at 2 cm voxels)
  if (o.frames < 0 || o.sessions < 0) throw InputError("--frames and --sessions must be >= 0");
  s.world = std::make_shared<const sim::World>(sim::World::load(sim::findWorld(o.world)));
  s.sessions = o.sessions > 0 ? o.sessions : s.world->sessionCount();
  if (s.sessions > s.world->sessionCount()) {
    throw InputError("--sessions " + std::to_string(o.sessions) + ": the world has " +
                     std::to_string(s.world->sessionCount()));
  }
  s.frames = o.frames;
  s.reference = o.reference;
  s.device = o.device;
  return s;
}

int runChecked(const DiffBenchOptions& o) {
  const DiffRunSettings settings = makeSettings(o);
  const std::string load_at_start = loadAverage();
  std::fprintf(stderr, "diff: %d sessions of %s at %.3f m\n", settings.sessions, o.world.c_str(),
               o.voxel_size_m);
  const DiffRun run = runDiff(settings);
  Json sessions = Json::array();
  for (const DiffSessionRun& s : run.sessions) sessions.push(diffSessionJson(s));
  Json report = Json::object()
                    .set("benchmark", "diff")
                    .set("machine", machineInfo(run.device_name, load_at_start))
                    .set("settings", settingsJson(o, settings))
                    .set("summary", diffSummaryJson(run))
                    .set("sessions", sessions)
                    .set("checks_passed", run.ok);
  emitReport(report, o.out_path);
  if (!run.ok) std::fprintf(stderr, "strata-bench diff: a self-check failed\n");
  return run.ok ? 0 : 1;
}

}  // namespace

CLI::App* addDiffCommand(CLI::App& app, DiffBenchOptions& o) {
  CLI::App* diff = app.add_subcommand("diff", "Multi-session change detection, per stage");
  diff->add_option("--world", o.world, "World name or YAML path")->capture_default_str();
  diff->add_option("--sessions", o.sessions, "Sessions (0: all of the world's)")
      ->capture_default_str();
  diff->add_option("--voxel-size", o.voxel_size_m, "Voxel edge, metres")->capture_default_str();
  diff->add_option("--frames", o.frames, "Frames per session, spread over its path (0: all)")
      ->capture_default_str();
  diff->add_flag("!--no-free-space", o.free_space, "Do not allocate free space");
  diff->add_flag("!--no-reference", o.reference, "Skip the C++ reference");
  diff->add_option("--out", o.out_path, "Also write the JSON report here (atomically)");
  diff->add_option("--device", o.device, "Vulkan device index or name substring");
  return diff;
}

int runDiffBench(const DiffBenchOptions& options) {
  try {
    return runChecked(options);
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata-bench diff: input error: %s\n", e.what());
    return 2;
  } catch (const DeviceError& e) {
    std::fprintf(stderr, "strata-bench diff: device error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata-bench diff: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::bench
