#include "cli/fuse_command.h"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cli/fuse_session.h"
#include "cli/option_checks.h"
#include "strata/core/error.h"
#include "strata/core/output_paths.h"

namespace strata::apps {
namespace {

namespace fs = std::filesystem;

bool analyticScene(const FuseOptions& o) { return o.dataset.empty() || o.dataset == "analytic"; }

/// The options alone, before the dataset is opened or a device is made (the parser refuses only
/// NaN, inf and unknown modes; tests call runFuse without it). MapConfig::validate checks the
/// rest after.
void validate(const FuseOptions& o) {
  const MapConfig& m = o.map;
  requireNumberIn(m.voxel_size_m, "--voxel-size", "metres", 0.001, 1.0);  // MapConfig's range
  requireNumber(o.truncation_m, "--truncation", "metres; 0: 4 voxels", 0.0, true);
  if (o.truncation_m > 0.0f && o.truncation_m < m.voxel_size_m) {
    throw InputError("--truncation " + std::to_string(o.truncation_m) +
                     " m is under one voxel (--voxel-size " + std::to_string(m.voxel_size_m) +
                     " m)");
  }
  requireNumber(m.max_weight, "--max-weight", "the weight clamp", 0.0, false);
  requireNumber(m.min_depth_m, "--min-depth", "metres", 0.0, true);
  requireNumber(m.max_depth_m, "--max-depth", "metres", 0.0, false);
  if (m.min_depth_m >= m.max_depth_m) {
    throw InputError("--min-depth " + std::to_string(m.min_depth_m) +
                     " m must be below --max-depth " + std::to_string(m.max_depth_m) + " m");
  }
  if (o.weight != "constant" && o.weight != "inv-z2") {
    throw InputError("--weight " + o.weight + " is not known (constant or inv-z2)");
  }
  if (o.distance != "point-to-plane" && o.distance != "along-ray") {
    throw InputError("--distance " + o.distance + " is not known (point-to-plane or along-ray)");
  }
  if (o.frames < 0) {
    throw InputError("--frames must be >= 0 (0: all; got " + std::to_string(o.frames) + ")");
  }
  if (o.stride < 1) {
    throw InputError("--stride must be at least 1 (got " + std::to_string(o.stride) + ")");
  }
  const std::string& format = o.dataset_options.format;
  if (format != "auto" && format != "tum" && format != "7scenes") {
    throw InputError("--format " + format + " is not known (auto, tum or 7scenes)");
  }
  requireFiniteHeight(o.slice_z_m, "--slice-z");
  if (o.dataset_options.depth_scale) {
    requireNumber(*o.dataset_options.depth_scale, "--depth-scale", "units per metre", 0.0, false);
  }
  if (!o.esdf_png_path.empty() && o.reference) {
    throw InputError("--esdf-png needs the ESDF, which runs on the device: drop --reference");
  }
  if (o.esdf && o.reference) throw InputError("--esdf runs on the device: drop --reference");
  if (o.track && o.reference) throw InputError("--track runs on the device: drop --reference");
  if (!o.trajectory_path.empty() && !o.track) throw InputError("--trajectory needs --track");
}

/// Every output against the dataset, the camera file and each other, before anything is read.
void checkPaths(const FuseOptions& o) {
  OutputPaths paths;
  if (!analyticScene(o)) {
    std::error_code error;
    if (fs::is_directory(o.dataset, error)) {
      paths.inputFolder(o.dataset, "the dataset folder");
    } else {
      paths.inputFile(o.dataset, "the dataset");
    }
  }
  paths.inputFile(o.dataset_options.camera_file, "--camera");
  paths.inputFile(o.dataset_options.trajectory_file, "the trajectory file");
  paths.outputFile(o.map_path, "--map");
  paths.outputFile(o.mesh_path, "--mesh");
  paths.outputFile(o.render_path, "--render");
  paths.outputFile(o.esdf_png_path, "--esdf-png");
  paths.outputFile(o.trajectory_path, "--trajectory");
  paths.check();
}

}  // namespace

CLI::App* addFuseCommand(CLI::App& app, FuseOptions& o) {
  CLI::App* fuse = app.add_subcommand("fuse", "Fuse an RGB-D dataset into a TSDF map");
  fuse->add_option("dataset", o.dataset,
                   "TUM RGB-D or 7-Scenes folder; omitted or 'analytic': the built-in scene");
  fuse->add_option("--voxel-size", o.map.voxel_size_m, "Voxel edge, metres (0.001 to 1)")
      ->check(finiteNumber())
      ->capture_default_str();
  fuse->add_option("--truncation", o.truncation_m, "Truncation distance, metres (default 4 voxels)")
      ->check(finiteNumber());
  fuse->add_option("--max-weight", o.map.max_weight, "Weight clamp")
      ->check(finiteNumber())
      ->capture_default_str();
  fuse->add_option("--min-depth", o.map.min_depth_m, "Ignore depth below, metres")
      ->check(finiteNumber())
      ->capture_default_str();
  fuse->add_option("--max-depth", o.map.max_depth_m, "Ignore depth beyond, metres")
      ->check(finiteNumber())
      ->capture_default_str();
  fuse->add_option("--weight", o.weight, "Observation weight: constant | inv-z2")
      ->check(CLI::IsMember({"constant", "inv-z2"}))
      ->capture_default_str();
  fuse->add_option("--distance", o.distance,
                   "Signed distance: point-to-plane (exact for planes) | along-ray (projective)")
      ->check(CLI::IsMember({"point-to-plane", "along-ray"}))
      ->capture_default_str();
  // NOTE: the counts are checked by runFuse (exit 2 naming the option and its range).
  fuse->add_option("--frames", o.frames, "Fuse at most N frames (0: all)");
  fuse->add_option("--stride", o.stride, "Use every N-th frame (at least 1)");
  fuse->add_option("--mesh", o.mesh_path, "Write the mesh here (binary PLY)");
  fuse->add_option("--map", o.map_path, "Write the map here (.strata)");
  fuse->add_option("--render", o.render_path, "Write a shaded rendering from the last pose (PNG)");
  fuse->add_option("--device", o.device, "Vulkan device index or name substring (env STRATA_DEVICE)");
  fuse->add_flag("--reference", o.reference, "Fuse with the C++ reference instead of the device");
  fuse->add_flag("--esdf", o.esdf,
                 "Keep the ESDF up to date incrementally while fusing (ESDF ms in the summary)");
  fuse->add_option("--esdf-png", o.esdf_png_path,
                   "Write a colour-mapped ESDF slice here at the end (implies --esdf)");
  fuse->add_option("--slice-z", o.slice_z_m, "Height of the ESDF slice, metres")
      ->check(finiteNumber())
      ->capture_default_str();
  // NOTE: callbacks, not an int flag: CLI11 writes 0 into an int flag that was not given.
  fuse->add_flag_callback(
      "--free-space", [&o] { o.free_space = 1; },
      "Also allocate the free space in front of surfaces, so the ESDF covers it (default with "
      "--esdf)");
  fuse->add_flag_callback(
      "--no-free-space", [&o] { o.free_space = 0; }, "Allocate only the surfaces' band");
  fuse->add_flag("--quiet", o.quiet, "No progress bar");
  fuse->add_flag("--skip-bad-frames", o.skip_bad_frames,
                 "Skip frames that cannot be read or are refused (named and counted) instead of "
                 "stopping without output");
  fuse->add_flag("--track", o.track,
                 "Track the frames against the map (frame-to-model ICP) instead of reading their "
                 "poses; the first frame keeps the dataset's pose; lost frames are not fused");
  fuse->add_option("--trajectory", o.trajectory_path,
                   "With --track: write the estimated poses here (TUM: t tx ty tz qx qy qz qw)");
  fuse->add_option("--format", o.dataset_options.format, "Dataset layout: auto | tum | 7scenes")
      ->check(CLI::IsMember({"auto", "tum", "7scenes"}));
  fuse->add_option("--camera", o.dataset_options.camera_file,
                   "Camera YAML (width, height, fx, fy, cx, cy, depth_scale)");
  fuse->add_option("--depth-scale", o.dataset_options.depth_scale, "Depth PNG units per metre")
      ->check(finiteNumber());
  return fuse;
}

int runFuse(FuseOptions o) {
  try {
    validate(o);
    checkPaths(o);
    if (o.truncation_m > 0.0f) o.map.truncation_voxels = o.truncation_m / o.map.voxel_size_m;
    o.map.weight_mode =
        o.weight == "inv-z2" ? WeightMode::kInverseDepthSquared : WeightMode::kConstant;
    o.map.distance_mode = o.distance == "along-ray" ? DistanceMode::kAlongRay
                                                    : DistanceMode::kPointToPlane;
    if (!o.esdf_png_path.empty()) o.esdf = true;
    // NOTE: a planner's ESDF needs distances in open space, which only allocated blocks carry.
    if (o.free_space >= 0) o.map.allocate_free_space = o.free_space == 1;
    if (o.free_space < 0 && o.esdf) o.map.allocate_free_space = true;
    o.map.validate();
    FuseSession session(o);
    // A run that stopped part-way writes nothing: a map of some of the frames at the path asked
    // for would pass for the whole dataset's (the files there stay as they were).
    if (!session.run()) return 1;
    const bool outputs_written = session.writeOutputs();
    session.printSummary();
    return outputs_written ? 0 : 1;
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata fuse: input error: %s\n", e.what());
    return 2;
  } catch (const DeviceError& e) {
    std::fprintf(stderr, "strata fuse: device error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata fuse: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::apps
