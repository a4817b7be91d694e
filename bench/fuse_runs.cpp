#include "fuse_runs.h"

#include <chrono>
#include <cstdio>

#include "strata/integrate/tsdf_integration.h"
#include "machine_info.h"
#include "strata/mesh/extract_mesh.h"
#include "summary.h"
#include "bench_timing.h"

namespace strata::bench {
namespace {

constexpr double kBytesPerMiB = 1024.0 * 1024.0;
constexpr std::size_t kProgressEvery = 25;  // frames between progress lines

double deviceTotalMs(const FrameStats& s) {
  return s.upload_ms + s.normals_ms + s.allocate_ms + s.integrate_ms;
}

/// One value per measured frame (warm-up excluded).
template <typename Field>
std::vector<double> measured(const DeviceRun& run, Field field) {
  std::vector<double> values;
  for (std::size_t i = kWarmupFrames; i < run.frames.size(); ++i) {
    values.push_back(field(run.frames[i]));
  }
  return values;
}

/// sum(touched_blocks * 512) / sum(normals + allocate + integrate device time), per second.
double voxelUpdatesPerSecond(const DeviceRun& run) {
  double voxels = 0.0, kernel_ms = 0.0;
  for (std::size_t i = kWarmupFrames; i < run.frames.size(); ++i) {
    const FrameStats& s = run.frames[i];
    voxels += static_cast<double>(s.touched_blocks) * kVoxelsPerBlock;
    kernel_ms += s.normals_ms + s.allocate_ms + s.integrate_ms;
  }
  return kernel_ms > 0.0 ? voxels / (kernel_ms / 1000.0) : 0.0;
}

void meshHostMap(DeviceFusion& fusion, DeviceRun& run) {
  TsdfMap host_map(fusion.config());
  auto start = Clock::now();
  fusion.map().download(host_map);
  run.download_ms = msSince(start);
  start = Clock::now();
  run.mesh = extractMesh(host_map);
  run.mesh_ms = msSince(start);
}

}  // namespace

DeviceRun runDevice(const MapConfig& config, const PreloadedFrames& data,
                    const std::string& device_selector, std::uint32_t prefill_blocks) {
  vk::ContextOptions options;
  options.device_selector = device_selector;
  options.log_device = false;
  auto context = vk::Context::create(options);
  DeviceRun run;
  run.device_name = context->deviceName();
  {
    DeviceFusion fusion(*context, config);
    if (prefill_blocks > 0) {
      // Unobserved blocks far from the scene (100 km away): a map that is large elsewhere.
      TsdfMap far(config);
      const int side = 100;
      for (std::uint32_t i = 0; i < prefill_blocks; ++i) {
        const int b = static_cast<int>(i);
        far.allocateBlock(BlockIndex(600000 + b % side, (b / side) % side, b / (side * side)));
      }
      fusion.map().upload(far);
    }
    const std::size_t count = data.frames.size();
    for (std::size_t i = 0; i < count; ++i) {
      run.frames.push_back(fusion.integrate(data.frames[i], data.intrinsics));
      run.blocks_after_frame.push_back(fusion.map().blockCount());
      if ((i + 1) % kProgressEvery == 0 || i + 1 == count) {
        std::fprintf(stderr, "  device: frame %zu/%zu, %u blocks\n", i + 1, count,
                     fusion.map().blockCount());
      }
    }
    run.block_capacity = fusion.map().blockCapacity();
    run.hash_capacity = fusion.map().hashCapacity();
    run.map_device_bytes = fusion.map().deviceBytes();
    run.host_rss_peak_mib = peakRssMiB();
    run.host_rss_now_mib = currentRssMiB();
    meshHostMap(fusion, run);
  }
  run.peak_device_bytes = context->peakAllocatedBytes();
  return run;
}

double meanDeviceTotalMs(const DeviceRun& run) { return mean(measured(run, deviceTotalMs)); }

double meanWallMs(const DeviceRun& run) {
  return mean(measured(run, [](const FrameStats& s) { return s.wall_ms; }));
}

Json deviceReport(const DeviceRun& run, bool& ok) {
  const std::uint32_t blocks = run.blocks_after_frame.empty() ? 0 : run.blocks_after_frame.back();
  const double voxels = static_cast<double>(blocks) * kVoxelsPerBlock;
  std::size_t growth_frames = 0;
  for (const FrameStats& s : run.frames) growth_frames += s.allocation_passes > 1 ? 1 : 0;
  const double wall_ms = meanWallMs(run);
  const bool map_ok = blocks > 0;
  const bool mesh_ok = !run.mesh.vertices.empty() && !run.mesh.triangles.empty();
  ok = ok && map_ok && mesh_ok;
  return Json::object()
      .set("frames_measured",
           run.frames.size() > kWarmupFrames ? run.frames.size() - kWarmupFrames : 0)
      .set("upload_ms", meanMedian(measured(run, [](const FrameStats& s) { return s.upload_ms; })))
      .set("normals_ms",
           meanMedian(measured(run, [](const FrameStats& s) { return s.normals_ms; })))
      .set("allocate_ms",
           meanMedian(measured(run, [](const FrameStats& s) { return s.allocate_ms; })))
      .set("integrate_ms",
           meanMedian(measured(run, [](const FrameStats& s) { return s.integrate_ms; })))
      .set("device_total_ms", meanMedian(measured(run, deviceTotalMs)))
      .set("wall_ms", meanMedian(measured(run, [](const FrameStats& s) { return s.wall_ms; })))
      .set("frames_per_s_wall", wall_ms > 0.0 ? 1000.0 / wall_ms : 0.0)
      .set("voxel_updates_per_s", voxelUpdatesPerSecond(run))
      .set("touched_blocks_per_frame",
           meanMedian(measured(run, [](const FrameStats& s) { return double(s.touched_blocks); })))
      .set("frames_with_growth_retry", growth_frames)
      .set("blocks_allocated", blocks)
      .set("block_capacity", run.block_capacity)
      .set("hash_capacity", run.hash_capacity)
      .set("bytes_per_voxel_payload", DeviceTsdfMap::kBytesPerVoxel)
      .set("map_device_bytes", run.map_device_bytes)
      .set("bytes_per_voxel_total",
           voxels > 0.0 ? static_cast<double>(run.map_device_bytes) / voxels : 0.0)
      .set("peak_device_mib", static_cast<double>(run.peak_device_bytes) / kBytesPerMiB)
      .set("host_rss_peak_mib", run.host_rss_peak_mib)
      .set("host_rss_now_mib", run.host_rss_now_mib)
      .set("mesh", Json::object()
                       .set("download_ms", run.download_ms)
                       .set("extract_ms", run.mesh_ms)
                       .set("vertices", run.mesh.vertices.size())
                       .set("triangles", run.mesh.triangles.size()))
      .set("checks", Json::object().set("map_non_empty", map_ok).set("mesh_non_empty", mesh_ok));
}

ReferenceRun runReference(const MapConfig& config, const PreloadedFrames& data,
                          std::size_t frame_count) {
  TsdfMap map(config);
  ReferenceRun run;
  for (std::size_t i = 0; i < frame_count; ++i) {
    const auto start = Clock::now();
    integrateFrameReference(map, data.frames[i], data.intrinsics, kReferenceThreads);
    run.frame_ms.push_back(msSince(start));
    if ((i + 1) % 5 == 0 || i + 1 == frame_count) {
      std::fprintf(stderr, "  reference: frame %zu/%zu, %.0f ms\n", i + 1, frame_count,
                   run.frame_ms.back());
    }
  }
  run.blocks = map.blockCount();
  return run;
}

Json referenceReport(const ReferenceRun& reference, const DeviceRun& device) {
  const std::size_t count = reference.frame_ms.size();
  std::vector<double> device_wall;  // the device's wall time on the same measured frames
  for (std::size_t i = kWarmupFrames; i < count && i < device.frames.size(); ++i) {
    device_wall.push_back(device.frames[i].wall_ms);
  }
  const std::vector<double> ms = tail(reference.frame_ms, kWarmupFrames);
  const double device_mean = mean(device_wall);
  return Json::object()
      .set("threads", kReferenceThreads)
      .set("frames", count)
      .set("frames_measured", ms.size())
      .set("ms_per_frame", meanMedian(ms))
      .set("device_wall_ms_same_frames", meanMedian(device_wall))
      .set("reference_over_device_wall", device_mean > 0.0 ? mean(ms) / device_mean : 0.0)
      .set("blocks_allocated", reference.blocks)
      .set("device_blocks_after_same_frames", count > 0 && count <= device.blocks_after_frame.size()
                                                  ? Json(device.blocks_after_frame[count - 1])
                                                  : Json());
}

}  // namespace strata::bench
