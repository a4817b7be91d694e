#include "cli/fuse_command.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>

#include "cli/fuse_session.h"
#include "strata/core/error.h"

namespace strata::apps {

CLI::App* addFuseCommand(CLI::App& app, FuseOptions& o) {
  CLI::App* fuse = app.add_subcommand("fuse", "Fuse an RGB-D dataset into a TSDF map");
  fuse->add_option("dataset", o.dataset,
                   "TUM RGB-D or 7-Scenes folder; omitted or 'analytic': the built-in scene");
  fuse->add_option("--voxel-size", o.map.voxel_size_m, "Voxel edge, metres")->capture_default_str();
  fuse->add_option("--truncation", o.truncation_m, "Truncation distance, metres (default 4 voxels)");
  fuse->add_option("--max-weight", o.map.max_weight, "Weight clamp")->capture_default_str();
  fuse->add_option("--min-depth", o.map.min_depth_m, "Ignore depth below, metres")
      ->capture_default_str();
  fuse->add_option("--max-depth", o.map.max_depth_m, "Ignore depth beyond, metres")
      ->capture_default_str();
  fuse->add_option("--weight", o.weight, "Observation weight: constant | inv-z2")
      ->check(CLI::IsMember({"constant", "inv-z2"}))
      ->capture_default_str();
  fuse->add_option("--distance", o.distance,
                   "Signed distance: point-to-plane (exact for planes) | along-ray (projective)")
      ->check(CLI::IsMember({"point-to-plane", "along-ray"}))
      ->capture_default_str();
  fuse->add_option("--frames", o.frames, "Fuse at most N frames (0: all)");
  fuse->add_option("--stride", o.stride, "Use every N-th frame")->check(CLI::PositiveNumber);
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
      ->capture_default_str();
  // NOTE: callbacks, not an int flag: CLI11 writes 0 into an int flag that was not given.
  fuse->add_flag_callback(
      "--free-space", [&o] { o.free_space = 1; },
      "Also allocate the free space in front of surfaces, so the ESDF covers it (default with "
      "--esdf)");
  fuse->add_flag_callback(
      "--no-free-space", [&o] { o.free_space = 0; }, "Allocate only the surfaces' band");
  fuse->add_flag("--quiet", o.quiet, "No progress bar");
  fuse->add_flag("--track", o.track,
                 "Track the frames against the map (frame-to-model ICP) instead of reading their "
                 "poses; the first frame keeps the dataset's pose; lost frames are not fused");
  fuse->add_option("--trajectory", o.trajectory_path,
                   "With --track: write the estimated poses here (TUM: t tx ty tz qx qy qz qw)");
  fuse->add_option("--format", o.dataset_options.format, "Dataset layout: auto | tum | 7scenes")
      ->check(CLI::IsMember({"auto", "tum", "7scenes"}));
  fuse->add_option("--camera", o.dataset_options.camera_file,
                   "Camera YAML (width, height, fx, fy, cx, cy, depth_scale)");
  fuse->add_option("--depth-scale", o.dataset_options.depth_scale, "Depth PNG units per metre");
  return fuse;
}

int runFuse(FuseOptions o) {
  try {
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
    if (o.frames < 0) throw InputError("--frames must be >= 0");
    if (o.esdf && o.reference) throw InputError("--esdf runs on the device: drop --reference");
    if (o.track && o.reference) throw InputError("--track runs on the device: drop --reference");
    if (!o.trajectory_path.empty() && !o.track) throw InputError("--trajectory needs --track");
    FuseSession session(o);
    const bool complete = session.run();
    const bool outputs_written = session.writeOutputs();
    session.printSummary();
    return complete && outputs_written ? 0 : 1;
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
