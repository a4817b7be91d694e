#include "fuse_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "strata/core/error.h"
#include "fuse_runs.h"
#include "machine_info.h"
#include "open3d_peer.h"
#include "preload.h"
#include "streaming_ceiling.h"
#include "bench_timing.h"

namespace strata::bench {
namespace {

Json intrinsicsJson(const CameraIntrinsics& k) {
  return Json::object()
      .set("width_px", k.width_px)
      .set("height_px", k.height_px)
      .set("fx_px", k.fx_px)
      .set("fy_px", k.fy_px)
      .set("cx_px", k.cx_px)
      .set("cy_px", k.cy_px);
}

Json fuseNotes() {
  return Json::array()
      .push(
          "device times (upload/normals/allocate/integrate) come from Vulkan timestamp "
          "queries; wall and CPU times from std::chrono::steady_clock")
      .push("every statistic leaves out the first " + std::to_string(kWarmupFrames) +
            " frames of its run (warm-up: shader compilation on first dispatch, first "
            "allocations)")
      .push("frames are decoded into memory before timing; decode time is not fusion time")
      .push(
          "voxel_updates_per_s = sum(touched_blocks * 512) / sum(normals + allocate + "
          "integrate device time) over the measured frames")
      .push(
          "bytes_per_voxel_total = DeviceTsdfMap::deviceBytes (pool capacity + hash table + "
          "counters) / (blocks_allocated * 512)")
      .push(
          "peak_device_mib is per voxel size (a fresh Vulkan context each); host_rss_peak_mib "
          "is the process peak so far (getrusage), so it includes the preloaded frames, the "
          "Open3D copies of them (host_rss_before_runs_mib - host_rss_after_preload_mib) and "
          "earlier voxel sizes; on lavapipe device memory is host memory too")
      .push(
          "on lavapipe the 'device' is the CPU: device time is CPU time on LP_NUM_THREADS "
          "threads, and timings are noisy when other work shares the cores");
}

constexpr const char* kOpen3dNotBuilt = "not built (configure with -DSTRATA_WITH_OPEN3D=ON)";

Json settingsJson(const FuseBenchOptions& options, const PreloadedFrames& data,
                  std::size_t reference_frames, double rss_before_runs_mib,
                  const Open3dPeer* peer) {
  Json voxel_sizes = Json::array();
  for (const float v : options.voxel_sizes_m) voxel_sizes.push(static_cast<double>(v));
  return Json::object()
      .set("data", options.data_dir)
      .set("dataset", data.dataset_name)
      .set("frames", data.frames.size())
      .set("warmup_frames_excluded", kWarmupFrames)
      .set("reference_frames", reference_frames)
      .set("prefill_blocks", options.prefill_blocks)
      .set("voxel_sizes_m", voxel_sizes)
      .set("preload_s", data.load_s)
      .set("host_rss_after_preload_mib", data.host_rss_mib)
      .set("host_rss_before_runs_mib", rss_before_runs_mib)
      .set("intrinsics", intrinsicsJson(data.intrinsics))
      .set("map_config", "default MapConfig except voxel_size_m (see results[].map_config)")
      .set("open3d", peer != nullptr ? peer->describe() : Json(kOpen3dNotBuilt))
      .set("notes", fuseNotes());
}

/// One voxel size: device run, reference run, Open3D peer (null: not built).
/// What the integration kernel moves against the streaming ceiling. Bytes are an upper bound:
/// every voxel of every touched block read and written (12 + 12 bytes); voxels that project
/// outside the image or behind the band are skipped by the kernel and move nothing.
Json ceilingReport(const DeviceRun& run, const StreamingCeiling& ceiling) {
  double bytes = 0.0;
  double ms = 0.0;
  std::size_t n = 0;
  for (std::size_t i = kWarmupFrames; i < run.frames.size(); ++i) {
    bytes += static_cast<double>(run.frames[i].touched_blocks) * kVoxelsPerBlock * 2.0 *
             DeviceTsdfMap::kBytesPerVoxel;
    ms += run.frames[i].integrate_ms;
    ++n;
  }
  if (n == 0 || ms <= 0.0) return Json();
  const double gb_per_s = bytes / (ms * 1e6);
  return Json::object()
      .set("integrate_voxel_bytes_per_frame_upper", bytes / static_cast<double>(n))
      .set("integrate_gb_per_s_upper", gb_per_s)
      .set("streaming_ceiling_gb_per_s", ceiling.gb_per_s)
      .set("ceiling_fraction_upper", ceiling.gb_per_s > 0.0 ? gb_per_s / ceiling.gb_per_s : 0.0);
}

Json runVoxelSize(float voxel_size_m, const FuseBenchOptions& options, const PreloadedFrames& data,
                  std::size_t reference_frames, Open3dPeer* peer,
                  const StreamingCeiling& ceiling, std::string& device_name, bool& ok) {
  MapConfig config;
  config.voxel_size_m = voxel_size_m;
  config.validate();
  std::fprintf(stderr, "voxel %.3f m: device fusion of %zu frames\n", voxel_size_m,
               data.frames.size());
  const DeviceRun device =
      runDevice(config, data, options.device, static_cast<std::uint32_t>(options.prefill_blocks));
  device_name = device.device_name;
  Json result = Json::object()
                    .set("voxel_size_m", static_cast<double>(voxel_size_m))
                    .set("truncation_m", static_cast<double>(config.truncationDistance()))
                    .set("map_config", config.describe())
                    .set("device", deviceReport(device, ok))
                    .set("integrate_vs_ceiling", ceilingReport(device, ceiling));
  if (reference_frames > 0) {
    std::fprintf(stderr, "voxel %.3f m: C++ reference on %zu frames\n", voxel_size_m,
                 reference_frames);
    result.set("reference", referenceReport(runReference(config, data, reference_frames), device));
  }
  if (peer == nullptr) {
    result.set("open3d", kOpen3dNotBuilt);
  } else {
    std::fprintf(stderr, "voxel %.3f m: Open3D peer\n", voxel_size_m);
    result.set("open3d", peer->run(config, device));
  }
  return result;
}

int runChecked(FuseBenchOptions options) {
  if (options.data_dir.empty()) options.data_dir = redkitchenDataDir();
  if (options.voxel_sizes_m.empty()) throw InputError("--voxel-sizes is empty");
  if (options.frames < 0 || options.reference_frames < 0 || options.prefill_blocks < 0) {
    throw InputError("--frames, --reference-frames and --prefill-blocks must be >= 0");
  }
  for (const float voxel_size_m : options.voxel_sizes_m) {
    MapConfig config;  // fail before the slow preload
    config.voxel_size_m = voxel_size_m;
    config.validate();
  }
  const std::string load_at_start = loadAverage();
  const PreloadedFrames data = preloadFrames(options.data_dir, options.frames);
  if (data.frames.size() <= kWarmupFrames) {
    throw InputError("need more than " + std::to_string(kWarmupFrames) +
                     " frames (the warm-up frames are not measured)");
  }
  const std::size_t reference_frames =
      std::min<std::size_t>(static_cast<std::size_t>(options.reference_frames), data.frames.size());
  const std::unique_ptr<Open3dPeer> peer = makeOpen3dPeer(data);  // frames converted, untimed
  StreamingCeiling ceiling;
  {
    vk::ContextOptions context_options;
    context_options.device_selector = options.device;
    context_options.log_device = false;
    auto context = vk::Context::create(context_options);
    std::fprintf(stderr, "streaming ceiling (copy kernel)\n");
    ceiling = measureStreamingCeiling(*context);
  }
  const double rss_before_runs_mib = currentRssMiB();
  Json results = Json::array();
  std::string device_name = "unknown";
  bool ok = true;
  for (const float voxel_size_m : options.voxel_sizes_m) {
    results.push(
        runVoxelSize(voxel_size_m, options, data, reference_frames, peer.get(), ceiling,
                     device_name, ok));
  }
  Json report = Json::object()
                    .set("benchmark", "fuse")
                    .set("machine", machineInfo(device_name, load_at_start))
                    .set("settings", settingsJson(options, data, reference_frames,
                                                  rss_before_runs_mib, peer.get()))
                    .set("streaming_ceiling", Json::object()
                                                  .set("gb_per_s", ceiling.gb_per_s)
                                                  .set("buffer_mib", ceiling.buffer_mib)
                                                  .set("repetitions", ceiling.repetitions))
                    .set("results", results)
                    .set("checks_passed", ok);
  emitReport(report, options.out_path);
  if (!ok) std::fprintf(stderr, "strata-bench fuse: a self-check failed (see \"checks\")\n");
  return ok ? 0 : 1;
}

}  // namespace

CLI::App* addFuseCommand(CLI::App& app, FuseBenchOptions& o) {
  CLI::App* fuse = app.add_subcommand("fuse", "TSDF fusion throughput on real RGB-D frames");
  o.data_dir = redkitchenDataDir();
  fuse->add_option("--data", o.data_dir, "TUM RGB-D or 7-Scenes folder")->capture_default_str();
  fuse->add_option("--voxel-sizes", o.voxel_sizes_m, "Voxel edges, metres, comma separated")
      ->delimiter(',')
      ->capture_default_str();
  fuse->add_option("--frames", o.frames, "Fuse the first N frames (0: all)")->capture_default_str();
  fuse->add_option("--reference-frames", o.reference_frames,
                   "Frames for the C++ reference (slow; 0 skips it)")
      ->capture_default_str();
  fuse->add_option("--prefill-blocks", o.prefill_blocks,
                   "Load this many unobserved blocks far from the scene first (map-size scaling)")
      ->capture_default_str();
  fuse->add_option("--out", o.out_path, "Also write the JSON report here (atomically)");
  fuse->add_option("--device", o.device,
                   "Vulkan device index or name substring (env "
                   "STRATA_DEVICE)");
  return fuse;
}

int runFuseBench(const FuseBenchOptions& options) {
  try {
    return runChecked(options);
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata-bench fuse: input error: %s\n", e.what());
    return 2;
  } catch (const DeviceError& e) {
    std::fprintf(stderr, "strata-bench fuse: device error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata-bench fuse: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::bench
