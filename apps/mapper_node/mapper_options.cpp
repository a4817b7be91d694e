#include "mapper_node/mapper_options.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>

#include "cli/option_checks.h"
#include "strata/core/error.h"
#include "strata/core/output_paths.h"

namespace strata::apps {

MapConfig MapperOptions::defaultMapperMapConfig() {
  MapConfig config;
  config.voxel_size_m = 0.05f;
  // NOTE: planners read the ESDF in free space, which only allocated blocks carry.
  config.allocate_free_space = true;
  return config;
}

std::string MapperOptions::objectsFile() const {
  if (!objects_path.empty() || map_path.empty()) return objects_path;
  return std::filesystem::path(map_path).replace_extension(".objects").string();
}

void MapperOptions::validate() const {
  map.validate();
  if (!std::isfinite(mesh_rate_hz)) throw InputError("--mesh-rate must be finite");
  if (!std::isfinite(esdf_rate_hz) || esdf_rate_hz < 0.0) {
    throw InputError("--esdf-rate must be >= 0 (0: no ESDF)");
  }
  if (!std::isfinite(stats_rate_hz) || stats_rate_hz <= 0.0) {
    throw InputError("--stats-rate must be > 0");
  }
  constexpr std::size_t kMaxQueueFrames = 10'000;  // far beyond use; a typo is refused
  if (queue_capacity < 1 || queue_capacity > kMaxQueueFrames) {
    throw InputError("--queue must be 1 to " + std::to_string(kMaxQueueFrames) + " frames, not " +
                     std::to_string(queue_capacity));
  }
  requireNumber(change_threshold_voxels, "--change-threshold", "voxels", 0.0, false);
  requireNumber(change_min_weight, "--change-min-weight", "frames", 0.0, false);
  if (!std::isfinite(esdf_slice_z_m)) throw InputError("--slice-z must be finite");
  if (!std::isfinite(save_every_s) || save_every_s < 0.0) {
    throw InputError("--save-every must be a finite number of seconds >= 0 (0: no timed saves)");
  }
  // The map and the object database are saved at the end of a session (and on SAVE_MAP): where
  // they would go is checked now, not after a whole session of mapping.
  OutputPaths paths;
  paths.outputFile(map_path, "--map");
  paths.outputFile(objectsFile(), "--objects");
  paths.check();
}

void addMapperOptions(CLI::App& app, MapperOptions& o) {
  app.add_option("--url", o.url, "LCM URL to listen on (udpm with ttl=0 stays on this host)")
      ->capture_default_str();
  app.add_option("--output-url", o.output_url, "LCM URL to publish on (default: --url)");
  app.add_option(
         "--map", o.map_path,
         "Map file: resumed at start when it exists; written on SAVE_MAP without a path and on "
         "SIGINT/SIGTERM ('' = none)")
      ->capture_default_str();
  app.add_option("--voxel-size", o.map.voxel_size_m, "Voxel edge, metres")
      ->check(finiteNumber())
      ->capture_default_str();
  app.add_option("--max-depth", o.map.max_depth_m, "Ignore depth beyond, metres")
      ->check(finiteNumber())
      ->capture_default_str();
  app.add_flag_callback(
      "--no-free-space", [&o] { o.map.allocate_free_space = false; },
      "Allocate only the surfaces' band (the ESDF then ends there)");
  app.add_option("--mesh-rate", o.mesh_rate_hz, "Mesh updates per second (<= 0: after every frame)")
      ->check(finiteNumber())
      ->capture_default_str();
  app.add_option("--esdf-rate", o.esdf_rate_hz, "ESDF slices per second (0: no ESDF)")
      ->check(finiteNumber())
      ->capture_default_str();
  app.add_option("--slice-z", o.esdf_slice_z_m, "Height of the ESDF slice, metres")
      ->check(finiteNumber())
      ->capture_default_str();
  app.add_option("--stats-rate", o.stats_rate_hz, "Least map_stats_t messages per second")
      ->check(finiteNumber())
      ->capture_default_str();
  app.add_option("--save-every", o.save_every_s,
                 "Save the map to --map every this many seconds while fusing (0: only on "
                 "SAVE_MAP and on exit)")
      ->check(finiteNumber())
      ->capture_default_str();
  app.add_option("--queue", o.queue_capacity, "Frames waiting to be fused (oldest dropped)")
      ->capture_default_str();
  app.add_flag_callback(
      "--no-change", [&o] { o.change_detection = false; },
      "No change detection (no change events; about half the device work)");
  app.add_option("--change-threshold", o.change_threshold_voxels,
                 "Change detection: distance difference that counts as change, voxels")
      ->check(finiteNumber())
      ->capture_default_str();
  app.add_option("--change-min-weight", o.change_min_weight,
                 "Change detection: frames that must see a voxel before it counts as observed")
      ->check(finiteNumber())
      ->capture_default_str();
  app.add_flag_callback(
      "--no-objects", [&o] { o.object_database = false; },
      "No object database (change events only)");
  app.add_option("--objects", o.objects_path,
                 "Object database file (default: beside --map, with .objects)");
  app.add_option("--objects-channel", o.channels.objects)->capture_default_str();
  app.add_flag_callback(
      "--no-keyframe-scores", [&o] { o.keyframe_scores = false; },
      "Do not score frames as keyframes (no keyframe_score_t)");
  app.add_option("--device", o.device, "Vulkan device index or name substring");
  app.add_option("--rgbd-channel", o.channels.rgbd)->capture_default_str();
  app.add_option("--camera-info-channel", o.channels.camera_info)->capture_default_str();
  app.add_option("--pose-channel", o.channels.pose)->capture_default_str();
  app.add_option("--command-channel", o.channels.command)->capture_default_str();
  app.add_option("--mesh-channel", o.channels.mesh)->capture_default_str();
  app.add_flag("--quiet", o.quiet, "Log only problems");
}

}  // namespace strata::apps
