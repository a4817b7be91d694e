#pragma once
// The measured runs of `strata-bench fuse`: the device path (DeviceFusion) and the C++ reference
// (integrateFrameReference) over preloaded frames, and their JSON reports.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "json.h"
#include "strata/integrate/device_fusion.h"
#include "strata/map/map_config.h"
#include "strata/mesh/mesh.h"
#include "preload.h"

namespace strata::bench {

/// Frames at the start of every run left out of all statistics: they pay one-off costs (lavapipe
/// compiles each shader on its first dispatch, first buffer allocations, map growth from empty).
constexpr std::size_t kWarmupFrames = 3;
/// Host threads of the C++ reference (the brief's fixed setting, so runs compare).
constexpr int kReferenceThreads = 2;

struct DeviceRun {
  std::string device_name;
  std::vector<FrameStats> frames;                 // every frame, warm-up included
  std::vector<std::uint32_t> blocks_after_frame;  // map blocks after each frame
  std::uint32_t block_capacity = 0;
  std::uint32_t hash_capacity = 0;
  std::uint64_t map_device_bytes = 0;   // DeviceTsdfMap::deviceBytes at the end
  std::uint64_t peak_device_bytes = 0;  // Context::peakAllocatedBytes (fresh context per run)
  double host_rss_peak_mib = 0.0;
  double host_rss_now_mib = 0.0;
  double download_ms = 0.0;  // device map -> host TsdfMap (steady_clock)
  double mesh_ms = 0.0;      // extractMesh on the host map (steady_clock)
  Mesh mesh;
};

/// Fuses every preloaded frame on a fresh Vulkan context, then downloads and meshes the map.
DeviceRun runDevice(const MapConfig& config, const PreloadedFrames& data,
                    const std::string& device_selector, std::uint32_t prefill_blocks = 0);
/// The "device" report; `ok` is cleared when the map or the mesh is empty.
Json deviceReport(const DeviceRun& run, bool& ok);

struct ReferenceRun {
  std::vector<double> frame_ms;  // steady_clock, every frame
  std::size_t blocks = 0;
};

/// integrateFrameReference with kReferenceThreads threads over the first `frame_count` frames.
ReferenceRun runReference(const MapConfig& config, const PreloadedFrames& data,
                          std::size_t frame_count);
Json referenceReport(const ReferenceRun& reference, const DeviceRun& device);

/// Mean device time of one measured frame: upload + normals + allocate + integrate.
double meanDeviceTotalMs(const DeviceRun& run);
/// Mean wall time of one measured frame.
double meanWallMs(const DeviceRun& run);

}  // namespace strata::bench
