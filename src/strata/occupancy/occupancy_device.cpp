#include "strata/core/clock.h"
#include "strata/occupancy/occupancy_device.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <string>
#include <vector>

#include "strata/core/error.h"
#include "strata/vk/dispatch_size.h"

namespace strata {
namespace {

constexpr std::uint32_t kRayGroupEdge = 16;  // occupancy_allocate / occupancy_mark: 16 x 16

using vk::divideUp;

OccupancyConfig validated(const OccupancyConfig& config) {
  config.validate();
  return config;
}

}  // namespace

DeviceOccupancy::DeviceOccupancy(DeviceTsdfMap& map, const OccupancyConfig& config)
    : map_(map),
      config_(validated(config)),
      allocate_pipeline_(vk::ComputePipeline::create(map.context(), "occupancy_allocate", 3,
                                                     sizeof(gpu::OccupancyRayPush))),
      mark_pipeline_(vk::ComputePipeline::create(map.context(), "occupancy_mark", 6,
                                                 sizeof(gpu::OccupancyRayPush))),
      update_pipeline_(vk::ComputePipeline::create(map.context(), "occupancy_update", 1,
                                                   sizeof(gpu::OccupancyUpdatePush))),
      counters_(vk::Buffer::create(map.context(), sizeof(gpu::OccupancyCounters),
                                   vk::MemoryUsage::kDeviceLocal, "occupancy counters")),
      readback_(vk::Buffer::create(map.context(), 16, vk::MemoryUsage::kHostReadback,
                                   "occupancy counters readback")),
      timer_(vk::TimestampQueries::create(map.context(), 4)) {
  static_assert(sizeof(gpu::MapCounters) == 16 && sizeof(gpu::OccupancyCounters) == 16);
  state_layer_ = map_.addLabelLayer();
  log_odds_layer_ = map_.addLabelLayer();
}

void DeviceOccupancy::stageDepth(const DepthImage& depth) {
  const std::uint64_t pixels = depth.depth_m.size();
  if (pixels > pixel_capacity_) {
    vk::Context& context = map_.context();
    depth_staging_ =
        vk::Buffer::create(context, pixels * 4, vk::MemoryUsage::kHostUpload, "depth staging");
    depth_ = vk::Buffer::create(context, pixels * 4, vk::MemoryUsage::kDeviceLocal, "depth image");
    pixel_capacity_ = pixels;
  }
  std::memcpy(depth_staging_.mapped(), depth.depth_m.data(), pixels * sizeof(float));
  width_px_ = depth.width_px;
  height_px_ = depth.height_px;
}

gpu::OccupancyRayPush DeviceOccupancy::rayPush(const FrameCamera& camera) const {
  // The reference's own conversion, so both kernels start from the same floats.
  const OccupancyRayCamera c = occupancyRayCamera(camera, config_, map_.config().voxel_size_m);
  gpu::OccupancyRayPush push{};
  std::copy(c.T_W_C, c.T_W_C + 16, push.T_W_C);
  std::copy(c.K_inv, c.K_inv + 4, push.K_inv);
  push.image_size[0] = static_cast<std::uint32_t>(camera.width_px);
  push.image_size[1] = static_cast<std::uint32_t>(camera.height_px);
  push.pixel_stride = config_.pixel_stride;
  push.min_depth_m = c.min_depth_m;
  push.max_range_m = c.max_range_m;
  push.inv_voxel_size = c.inv_voxel_size;
  return push;
}

void DeviceOccupancy::rayGroups(std::uint32_t& x, std::uint32_t& y) const {
  const std::uint32_t stride = config_.pixel_stride;
  x = divideUp(divideUp(static_cast<std::uint32_t>(width_px_), stride), kRayGroupEdge);
  y = divideUp(divideUp(static_cast<std::uint32_t>(height_px_), stride), kRayGroupEdge);
}

OccupancyFrameStats DeviceOccupancy::integrate(const RgbdFrame& frame,
                                               const CameraIntrinsics& intrinsics) {
  const auto wall_start = std::chrono::steady_clock::now();
  intrinsics.validate();
  validateFrame(frame, intrinsics);
  const FrameCamera camera = FrameCamera::from(intrinsics, frame.T_W_C);
  stageDepth(frame.depth);
  map_.maintainLoadFactor();

  OccupancyFrameStats stats;
  bool upload = true;
  allocate(camera, !exact_allocation_, upload, stats);
  gpu::OccupancyCounters marked = mark(camera, stats);
  if (marked.missing_blocks > 0 && !exact_allocation_) {
    // The block walk skipped a block at a corner: the voxel walk allocates exactly, and marking
    // again is harmless (marks are bits, set twice they are set once; a new frame id lists every
    // block once more from an empty list).
    stats.exact_fallbacks += 1;
    allocate(camera, false, upload, stats);
    marked = mark(camera, stats);
  }
  if (marked.missing_blocks > 0) {
    throw DeviceError("occupancy: " + std::to_string(marked.missing_blocks) +
                      " ray segments found no allocated block after the exact allocation pass "
                      "(allocation and mark traversals disagree)");
  }
  stats.touched_blocks = marked.touched_count;
  if (marked.touched_count > 0) runUpdate(marked.touched_count, stats);
  stats.wall_ms =
      msSince(wall_start);
  return stats;
}

void DeviceOccupancy::allocate(const FrameCamera& camera, bool walk_blocks, bool& upload,
                               OccupancyFrameStats& stats) {
  for (;;) {
    gpu::OccupancyRayPush push = rayPush(camera);
    push.hash_mask = map_.hashMask();
    push.walk_blocks = walk_blocks ? 1u : 0u;
    const gpu::MapCounters counters = runAllocation(push, upload, stats);
    upload = false;
    // Slots handed out must exist before the mark pass writes them (throws if they cannot).
    map_.commitBlockCount(counters.block_count);
    if (counters.hash_failures == 0) break;
    map_.growHash(map_.hashCapacity() * 2);  // the pass is idempotent: run it again
  }
  ensureSlotBuffers();
}

gpu::OccupancyCounters DeviceOccupancy::mark(const FrameCamera& camera,
                                             OccupancyFrameStats& stats) {
  gpu::OccupancyRayPush push = rayPush(camera);
  push.hash_mask = map_.hashMask();
  push.frame_id = ++frame_id_;
  push.state_address = map_.labelPoolAddress(state_layer_);  // after any growth of the pool
  return runMark(push, stats);
}

void DeviceOccupancy::download(OccupancyMap& out) {
  const std::uint32_t blocks = map_.blockCount();
  const std::size_t voxels = std::size_t{blocks} * kVoxelsPerBlock;
  std::vector<std::uint32_t> states(voxels), log_odds_bits(voxels);
  if (blocks > 0) {
    vk::download(map_.context(), map_.labelPool(state_layer_), states.data(), voxels * 4);
    vk::download(map_.context(), map_.labelPool(log_odds_layer_), log_odds_bits.data(), voxels * 4);
  }
  out = OccupancyMap(map_.config().voxel_size_m);
  for (const auto& [index, slot] : map_.blockSlots()) {
    if (slot >= blocks) continue;
    OccupancyBlock& block = out.allocateBlock(index);
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      const std::size_t at = std::size_t{slot} * kVoxelsPerBlock + i;
      block[i].state = states[at];
      std::memcpy(&block[i].log_odds, &log_odds_bits[at], sizeof(float));
    }
  }
  out.pruneUnobserved();
}

}  // namespace strata
