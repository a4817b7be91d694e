#include "strata/core/clock.h"
#include "strata/integrate/device_fusion.h"

#include <algorithm>
#include <chrono>
#include <cstring>

#include "strata/core/error.h"
#include "strata/integrate/block_allocation.h"
#include "strata/vk/dispatch_size.h"

namespace strata {
namespace {

constexpr std::uint32_t kMinTouchedCapacity = 4096;
// Pool headroom kept ahead of each frame, in touched blocks of the previous frame: a frame
// rarely allocates more new blocks than the last one touched.
constexpr std::uint32_t kMinReserveBlocks = 4096;
constexpr VkDeviceSize kGatherArgsOffset = 16;  // integrate_args.comp: args[4..6]

using vk::divideUp;

/// The camera fields every pass's push constants share (K, image size, depth range).
template <typename Push>
void setCamera(Push& push, const FrameCamera& camera, const MapConfig& config) {
  for (int i = 0; i < 4; ++i) push.K[i] = camera.K[i];
  push.image_size[0] = static_cast<std::uint32_t>(camera.width_px);
  push.image_size[1] = static_cast<std::uint32_t>(camera.height_px);
  push.min_depth_m = config.min_depth_m;
  push.max_depth_m = config.max_depth_m;
}

struct ArgsPush {
  std::uint32_t touched_capacity;
  std::uint32_t block_capacity;
};

}  // namespace

DeviceFusion::DeviceFusion(vk::Context& context, const MapConfig& config)
    : context_(context),
      map_(context, config),
      allocate_pipeline_(vk::ComputePipeline::create(context, "allocate_blocks", 5,
                                                     sizeof(gpu::AllocatePush))),
      integrate_pipeline_(vk::ComputePipeline::create(context, "integrate_tsdf", 6,
                                                      sizeof(gpu::IntegratePush))),
      normals_pipeline_(vk::ComputePipeline::create(context, "estimate_normals", 3,
                                                    sizeof(gpu::NormalsPush))),
      args_pipeline_(vk::ComputePipeline::create(context, "integrate_args", 2, sizeof(ArgsPush))),
      commands_(vk::CommandBuffer::create(context)),
      dispatch_args_(vk::Buffer::create(context, 32, vk::MemoryUsage::kDeviceLocal,
                                        "integration dispatch arguments")),
      counters_readback_(vk::Buffer::create(context, sizeof(gpu::MapCounters),
                                            vk::MemoryUsage::kHostReadback, "counters readback")),
      timer_(vk::TimestampQueries::create(context, 5)) {}

const vk::DescriptorSet& DeviceFusion::cachedSet(CachedSet& cache,
                                                 const vk::ComputePipeline& pipeline,
                                                 const std::vector<const vk::Buffer*>& buffers) {
  std::vector<std::uint64_t> ids(buffers.size());
  for (std::size_t i = 0; i < buffers.size(); ++i) ids[i] = buffers[i]->id();
  if (ids != cache.ids || cache.set.handle() == VK_NULL_HANDLE) {
    cache.set = vk::DescriptorSet::create(context_, pipeline, buffers);
    cache.ids = std::move(ids);
  }
  return cache.set;
}

void DeviceFusion::ensureFrameBuffers(std::size_t pixel_count, std::uint32_t tile_count) {
  if (pixel_count > pixel_capacity_) {
    const std::size_t depth_bytes = pixel_count * 4;
    // Packed RGB, 3 bytes a pixel, plus one word so the kernel may read a pixel's next word.
    const std::size_t color_bytes = (pixel_count * 3 + 3) / 4 * 4 + 4;
    depth_staging_ =
        vk::Buffer::create(context_, depth_bytes, vk::MemoryUsage::kHostUpload, "depth staging");
    color_staging_ =
        vk::Buffer::create(context_, color_bytes, vk::MemoryUsage::kHostUpload, "colour staging");
    depth_ = vk::Buffer::create(context_, depth_bytes, vk::MemoryUsage::kDeviceLocal, "depth image");
    color_ = vk::Buffer::create(context_, color_bytes, vk::MemoryUsage::kDeviceLocal, "colour image");
    normals_ = vk::Buffer::create(context_, depth_bytes * 4, vk::MemoryUsage::kDeviceLocal,
                                  "depth normals");
    std::memset(color_staging_.mapped(), 0, color_bytes);
    pixel_capacity_ = pixel_count;
  }
  if (tile_count > tile_capacity_) {
    quarter_ranges_ = vk::Buffer::create(context_, std::uint64_t{tile_count} * 8 * 4,
                                         vk::MemoryUsage::kDeviceLocal, "quarter-tile depth ranges");
    tile_capacity_ = tile_count;
  }
}

void DeviceFusion::reserveAhead() {
  map_.maintainLoadFactor();
  const std::uint32_t headroom = std::max(kMinReserveBlocks, last_touched_count_);
  map_.reserveBlocks(map_.blockCount() + headroom);
  const std::uint32_t wanted_touched =
      std::max(kMinTouchedCapacity, last_touched_count_ + last_touched_count_ / 2);
  if (wanted_touched > touched_capacity_) {
    touched_ = vk::Buffer::create(context_, std::uint64_t{wanted_touched} * 4,
                                  vk::MemoryUsage::kDeviceLocal, "touched blocks");
    touched_capacity_ = wanted_touched;
  }
  if (track_touched_ && (!touched_keys_.valid() || touched_keys_.size() < touched_capacity_ * 8ull)) {
    touched_keys_ = vk::Buffer::create(context_, std::uint64_t{touched_capacity_} * 8,
                                       vk::MemoryUsage::kHostReadback, "touched block keys");
  }
}

void DeviceFusion::stageFrame(const RgbdFrame& frame) {
  std::memcpy(depth_staging_.mapped(), frame.depth.depth_m.data(),
              frame.depth.depth_m.size() * sizeof(float));
  // Colour goes up as the frame holds it (packed RGB); integrate_tsdf.comp unpacks per voxel.
  if (!frame.color.empty()) {
    std::memcpy(color_staging_.mapped(), frame.color.rgb.data(), frame.color.rgb.size());
  }
}

FrameStats DeviceFusion::integrate(const RgbdFrame& frame, const CameraIntrinsics& intrinsics,
                                   int layer) {
  const auto wall_start = std::chrono::steady_clock::now();
  map_.poolAddress(layer);  // throws InputError for a layer the map lacks
  intrinsics.validate();
  validateFrame(frame, intrinsics);
  const FrameCamera camera = FrameCamera::from(intrinsics, frame.T_W_C);
  tile_count_ = divideUp(static_cast<std::uint32_t>(camera.width_px), gpu::kAllocationTilePx) *
                divideUp(static_cast<std::uint32_t>(camera.height_px), gpu::kAllocationTilePx);
  ensureFrameBuffers(frame.depth.depth_m.size(), tile_count_);
  reserveAhead();
  stageFrame(frame);

  FrameStats stats;
  const gpu::MapCounters counters = runPasses(camera, !frame.color.empty(), layer, stats);
  stats.touched_blocks = counters.touched_count;
  last_touched_count_ = counters.touched_count;
  last_touched_.clear();
  if (track_touched_) readTouchedBlocks(counters.touched_count);
  stats.wall_ms = msSince(wall_start);
  return stats;
}

gpu::MapCounters DeviceFusion::runPasses(const FrameCamera& camera, bool has_color, int layer,
                                         FrameStats& stats) {
  const std::uint32_t blocks_before = map_.blockCount();
  try {
    gpu::MapCounters counters = runPass(camera, true, has_color, layer, stats);
    while (growAfterOverflow(counters)) counters = runPass(camera, false, has_color, layer, stats);
    // Slots handed out must exist before anything reads them (throws and rolls back if not).
    map_.commitBlockCount(counters.block_count);
    return counters;
  } catch (const DeviceError&) {
    // Only a pass that did not overflow integrates, and none did: refuse the frame whole, so
    // its blocks neither linger unobserved in the map nor use up the block budget.
    map_.forgetBlocksFrom(blocks_before);
    throw;
  }
}

bool DeviceFusion::growAfterOverflow(const gpu::MapCounters& counters) {
  bool again = false;
  if (counters.block_count > map_.blockCapacity()) {
    map_.commitBlockCount(counters.block_count);  // grows, or throws and rolls the table back
    again = true;
  }
  if (counters.hash_failures > 0) {
    map_.growHash(map_.hashCapacity() * 2);
    again = true;
  }
  if (counters.touched_count > touched_capacity_) {
    last_touched_count_ = counters.touched_count;  // reserveAhead sizes the list from it
    again = true;
  }
  if (again) reserveAhead();
  return again;
}

gpu::MapCounters DeviceFusion::runPass(const FrameCamera& camera, bool first_pass, bool has_color,
                                       int layer, FrameStats& stats) {
  vk::CommandBuffer& cmd = commands_;
  cmd.begin();
  cmd.resetQueries(timer_);
  cmd.writeTimestamp(timer_, 0);
  if (first_pass) {
    const VkDeviceSize pixels = static_cast<VkDeviceSize>(camera.width_px) * camera.height_px;
    cmd.copy(depth_staging_, depth_, pixels * 4);
    if (has_color) cmd.copy(color_staging_, color_, color_staging_.size());
    // Quarter ranges start empty: smallest at all ones, largest at zero.
    const VkDeviceSize half = VkDeviceSize{tile_count_} * 4 * 4;
    cmd.fill(quarter_ranges_, 0xFFFFFFFFu, 0, half);
    cmd.fill(quarter_ranges_, 0u, half, half);
  }
  cmd.fill(map_.counters(), 0u, offsetof(gpu::MapCounters, touched_count), 8);
  cmd.barrier();
  cmd.writeTimestamp(timer_, 1);
  if (first_pass) recordNormals(cmd, camera);
  cmd.writeTimestamp(timer_, 2);
  recordAllocation(cmd, camera);
  cmd.writeTimestamp(timer_, 3);
  recordIntegration(cmd, camera, has_color, layer);
  if (track_touched_) recordTouchedGather(cmd);
  cmd.writeTimestamp(timer_, 4);
  cmd.copy(map_.counters(), counters_readback_, sizeof(gpu::MapCounters));
  cmd.barrier();
  cmd.end();
  cmd.submitAndWait();

  stats.upload_ms += timer_.elapsedMs(0, 1);
  stats.normals_ms += timer_.elapsedMs(1, 2);
  stats.allocate_ms += timer_.elapsedMs(2, 3);
  stats.integrate_ms += timer_.elapsedMs(3, 4);
  stats.allocation_passes += 1;
  gpu::MapCounters counters{};
  std::memcpy(&counters, counters_readback_.mapped(), sizeof(counters));
  return counters;
}

void DeviceFusion::recordNormals(vk::CommandBuffer& cmd, const FrameCamera& camera) {
  gpu::NormalsPush push{};
  setCamera(push, camera, config());
  push.max_relative_jump = config().normal_max_relative_jump;
  push.flags = config().distance_mode == DistanceMode::kPointToPlane ? gpu::kNormalsFlagWrite : 0u;
  push.tiles_x = divideUp(push.image_size[0], gpu::kAllocationTilePx);
  push.tile_count = tile_count_;
  cmd.bind(normals_pipeline_,
           cachedSet(normals_set_, normals_pipeline_, {&depth_, &normals_, &quarter_ranges_}));
  cmd.pushConstants(normals_pipeline_, &push, sizeof(push));
  cmd.dispatch(divideUp(push.image_size[0], 16), divideUp(push.image_size[1], 16));
  cmd.barrier();
}

void DeviceFusion::recordAllocation(vk::CommandBuffer& cmd, const FrameCamera& camera) {
  gpu::AllocatePush push{};
  gpu::storeMatrix(camera.T_W_C, push.T_W_C);
  setCamera(push, camera, config());
  push.truncation_m = config().truncationDistance();
  push.block_size_m = config().blockSize();
  push.hash_mask = map_.hashMask();
  push.pass_id = ++pass_id_;
  push.touched_capacity = touched_capacity_;
  push.free_space_stride = config().allocate_free_space ? config().free_space_pixel_stride : 0u;
  push.max_slab_depth_m = maxSlabDepth(config());
  cmd.bind(allocate_pipeline_,
           cachedSet(allocate_set_, allocate_pipeline_,
                     {&map_.hashEntries(), &map_.counters(), &touched_, &depth_, &quarter_ranges_}));
  cmd.pushConstants(allocate_pipeline_, &push, sizeof(push));
  constexpr std::uint32_t kGroupPx = 8 * gpu::kAllocationTilePx;  // 8 x 8 tiles per group
  cmd.dispatch(divideUp(push.image_size[0], kGroupPx), divideUp(push.image_size[1], kGroupPx));
  cmd.barrier();

  const ArgsPush args{touched_capacity_, map_.blockCapacity()};
  cmd.bind(args_pipeline_,
           cachedSet(args_set_, args_pipeline_, {&map_.counters(), &dispatch_args_}));
  cmd.pushConstants(args_pipeline_, &args, sizeof(args));
  cmd.dispatch(1);
  cmd.barrier();
}

void DeviceFusion::recordIntegration(vk::CommandBuffer& cmd, const FrameCamera& camera,
                                     bool has_color, int layer) {
  gpu::IntegratePush push{};
  gpu::storeMatrix(camera.T_C_W, push.T_C_W);
  setCamera(push, camera, config());
  push.voxel_size_m = config().voxel_size_m;
  push.truncation_m = config().truncationDistance();
  push.max_weight = config().max_weight;
  push.dropoff_start_m = config().dropoff_start_voxels * config().voxel_size_m;
  push.pool_address = map_.poolAddress(layer);
  push.weight_mode = static_cast<std::uint32_t>(config().weight_mode);
  push.flags = (config().weight_dropoff ? gpu::kFlagWeightDropoff : 0u) |
               (has_color ? gpu::kFlagHasColor : 0u) |
               (config().distance_mode == DistanceMode::kPointToPlane ? gpu::kFlagPointToPlane
                                                                      : 0u);
  cmd.bind(integrate_pipeline_,
           cachedSet(integrate_set_, integrate_pipeline_,
                     {&map_.hashEntries(), &touched_, &depth_, &color_, &map_.counters(),
                      &normals_}));
  cmd.pushConstants(integrate_pipeline_, &push, sizeof(push));
  cmd.dispatchIndirect(dispatch_args_, 0);
  cmd.barrier();
}

void DeviceFusion::setTrackTouchedBlocks(bool on) {
  track_touched_ = on;
  last_touched_.clear();
  if (on && touched_keys_pipeline_.pipeline() == VK_NULL_HANDLE) {
    touched_keys_pipeline_ = vk::ComputePipeline::create(context_, "gather_touched_blocks", 4, 0);
  }
}

void DeviceFusion::recordTouchedGather(vk::CommandBuffer& cmd) {
  cmd.bind(touched_keys_pipeline_,
           cachedSet(gather_set_, touched_keys_pipeline_,
                     {&map_.hashEntries(), &touched_, &map_.counters(), &touched_keys_}));
  cmd.dispatchIndirect(dispatch_args_, kGatherArgsOffset);
  cmd.barrier();
}

void DeviceFusion::readTouchedBlocks(std::uint32_t touched) {
  // A readback buffer, so always mapped (staged memory too); the submission ended with barrier().
  const auto* keys = static_cast<const std::uint64_t*>(touched_keys_.mapped());
  last_touched_.resize(touched);
  for (std::uint32_t i = 0; i < touched; ++i) last_touched_[i] = unpackBlockKey(keys[i]);
}

}  // namespace strata
