#include "integrate/device_fusion.h"

#include <algorithm>
#include <chrono>
#include <cstring>

#include "core/error.h"

namespace strata {
namespace {

constexpr std::uint32_t kMaxGroupsPerDimension = 65535;

std::uint32_t divideUp(std::uint32_t a, std::uint32_t b) { return (a + b - 1) / b; }

}  // namespace

DeviceFusion::DeviceFusion(vk::Context& context, const MapConfig& config)
    : context_(context),
      map_(context, config),
      allocate_pipeline_(vk::ComputePipeline::create(context, "allocate_blocks", 4,
                                                     sizeof(gpu::AllocatePush))),
      integrate_pipeline_(vk::ComputePipeline::create(context, "integrate_tsdf", 6,
                                                      sizeof(gpu::IntegratePush))),
      normals_pipeline_(vk::ComputePipeline::create(context, "estimate_normals", 2,
                                                    sizeof(gpu::NormalsPush))),
      counters_readback_(vk::Buffer::create(context, sizeof(gpu::MapCounters),
                                            vk::MemoryUsage::kHostReadback, "counters readback")),
      timer_(vk::TimestampQueries::create(context, 4)) {}

void DeviceFusion::ensureFrameBuffers(std::size_t pixel_count) {
  if (pixel_count <= pixel_capacity_) return;
  const std::size_t bytes = pixel_count * 4;
  depth_staging_ = vk::Buffer::create(context_, bytes, vk::MemoryUsage::kHostUpload, "depth staging");
  color_staging_ = vk::Buffer::create(context_, bytes, vk::MemoryUsage::kHostUpload, "colour staging");
  depth_ = vk::Buffer::create(context_, bytes, vk::MemoryUsage::kDeviceLocal, "depth image");
  color_ = vk::Buffer::create(context_, bytes, vk::MemoryUsage::kDeviceLocal, "colour image");
  normals_ = vk::Buffer::create(context_, bytes * 4, vk::MemoryUsage::kDeviceLocal, "depth normals");
  pixel_capacity_ = pixel_count;
}

void DeviceFusion::stageFrame(const RgbdFrame& frame) {
  std::memcpy(depth_staging_.mapped(), frame.depth.depth_m.data(),
              frame.depth.depth_m.size() * sizeof(float));
  if (frame.color.empty()) return;
  auto* packed = static_cast<std::uint32_t*>(color_staging_.mapped());
  const std::size_t pixels = frame.depth.depth_m.size();
  for (std::size_t i = 0; i < pixels; ++i) {
    const std::uint8_t* rgb = &frame.color.rgb[i * 3];
    packed[i] = packRgb(rgb[0], rgb[1], rgb[2]);
  }
}

FrameStats DeviceFusion::integrate(const RgbdFrame& frame, const CameraIntrinsics& intrinsics,
                                   int layer) {
  const auto wall_start = std::chrono::steady_clock::now();
  map_.poolAddress(layer);  // throws InputError for a layer the map lacks
  intrinsics.validate();
  validateFrame(frame, intrinsics);
  const FrameCamera camera = FrameCamera::from(intrinsics, frame.T_W_C);
  ensureFrameBuffers(frame.depth.depth_m.size());
  if (touched_capacity_ == 0) {
    touched_capacity_ = 4096;
    touched_ = vk::Buffer::create(context_, touched_capacity_ * 4, vk::MemoryUsage::kDeviceLocal,
                                  "touched blocks");
  }
  stageFrame(frame);
  map_.maintainLoadFactor();

  FrameStats stats;
  gpu::MapCounters counters{};
  bool upload_frame = true;
  for (;;) {
    counters = runAllocation(camera, upload_frame, stats);
    upload_frame = false;
    // Slots handed out must exist before anything reads them (throws and rolls back if not).
    map_.commitBlockCount(counters.block_count);
    bool retry = false;
    if (counters.hash_failures > 0) {
      map_.growHash(map_.hashCapacity() * 2);
      retry = true;
    }
    if (counters.touched_count > touched_capacity_) {
      touched_capacity_ = counters.touched_count + counters.touched_count / 2;
      touched_ = vk::Buffer::create(context_, std::uint64_t{touched_capacity_} * 4,
                                    vk::MemoryUsage::kDeviceLocal, "touched blocks");
      retry = true;
    }
    if (!retry) break;
  }
  stats.touched_blocks = counters.touched_count;
  last_touched_.clear();
  if (counters.touched_count > 0) {
    runIntegration(camera, !frame.color.empty(), counters.touched_count, layer, stats);
  }
  stats.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() -
                                                            wall_start).count();
  return stats;
}

gpu::MapCounters DeviceFusion::runAllocation(const FrameCamera& camera, bool upload_frame,
                                             FrameStats& stats) {
  gpu::AllocatePush push{};
  gpu::storeMatrix(camera.T_W_C, push.T_W_C);
  for (int i = 0; i < 4; ++i) push.K[i] = camera.K[i];
  push.image_size[0] = static_cast<std::uint32_t>(camera.width_px);
  push.image_size[1] = static_cast<std::uint32_t>(camera.height_px);
  push.min_depth_m = config().min_depth_m;
  push.max_depth_m = config().max_depth_m;
  push.truncation_m = config().truncationDistance();
  push.block_size_m = config().blockSize();
  push.hash_mask = map_.hashMask();
  push.pass_id = ++pass_id_;
  push.touched_capacity = touched_capacity_;
  push.free_space_stride = config().allocate_free_space ? config().free_space_pixel_stride : 0u;

  vk::DescriptorSet set = vk::DescriptorSet::create(
      context_, allocate_pipeline_, {&map_.hashEntries(), &map_.counters(), &touched_, &depth_});
  vk::DescriptorSet normals_set =
      vk::DescriptorSet::create(context_, normals_pipeline_, {&depth_, &normals_});
  gpu::NormalsPush normals_push{};
  for (int i = 0; i < 4; ++i) normals_push.K[i] = camera.K[i];
  normals_push.image_size[0] = push.image_size[0];
  normals_push.image_size[1] = push.image_size[1];
  normals_push.min_depth_m = push.min_depth_m;
  normals_push.max_depth_m = push.max_depth_m;
  normals_push.max_relative_jump = config().normal_max_relative_jump;
  vk::CommandBuffer cmd = vk::CommandBuffer::create(context_);
  cmd.begin();
  cmd.resetQueries(timer_);
  cmd.writeTimestamp(timer_, 0);
  if (upload_frame) {
    const VkDeviceSize bytes = static_cast<VkDeviceSize>(camera.width_px) * camera.height_px * 4;
    cmd.copy(depth_staging_, depth_, bytes);
    cmd.copy(color_staging_, color_, bytes);
  }
  cmd.fill(map_.counters(), 0u, offsetof(gpu::MapCounters, touched_count), 8);
  cmd.barrier();
  cmd.writeTimestamp(timer_, 1);
  if (upload_frame && config().distance_mode == DistanceMode::kPointToPlane) {
    cmd.bind(normals_pipeline_, normals_set);
    cmd.pushConstants(normals_pipeline_, &normals_push, sizeof(normals_push));
    cmd.dispatch(divideUp(push.image_size[0], 16), divideUp(push.image_size[1], 16));
    cmd.barrier();
  }
  cmd.writeTimestamp(timer_, 2);
  cmd.bind(allocate_pipeline_, set);
  cmd.pushConstants(allocate_pipeline_, &push, sizeof(push));
  cmd.dispatch(divideUp(push.image_size[0], 16), divideUp(push.image_size[1], 16));
  cmd.barrier();
  cmd.writeTimestamp(timer_, 3);
  cmd.copy(map_.counters(), counters_readback_, sizeof(gpu::MapCounters));
  cmd.barrier();
  cmd.end();
  cmd.submitAndWait();

  stats.upload_ms += timer_.elapsedMs(0, 1);
  stats.normals_ms += timer_.elapsedMs(1, 2);
  stats.allocate_ms += timer_.elapsedMs(2, 3);
  stats.allocation_passes += 1;
  gpu::MapCounters counters{};
  std::memcpy(&counters, counters_readback_.mapped(), sizeof(counters));
  return counters;
}

void DeviceFusion::runIntegration(const FrameCamera& camera, bool has_color,
                                  std::uint32_t touched, int layer, FrameStats& stats) {
  gpu::IntegratePush push{};
  gpu::storeMatrix(camera.T_C_W, push.T_C_W);
  for (int i = 0; i < 4; ++i) push.K[i] = camera.K[i];
  push.image_size[0] = static_cast<std::uint32_t>(camera.width_px);
  push.image_size[1] = static_cast<std::uint32_t>(camera.height_px);
  push.min_depth_m = config().min_depth_m;
  push.max_depth_m = config().max_depth_m;
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

  vk::DescriptorSet set = vk::DescriptorSet::create(
      context_, integrate_pipeline_,
      {&map_.hashEntries(), &touched_, &depth_, &color_, &map_.counters(), &normals_});
  vk::CommandBuffer cmd = vk::CommandBuffer::create(context_);
  cmd.begin();
  cmd.resetQueries(timer_);
  cmd.writeTimestamp(timer_, 0);
  cmd.bind(integrate_pipeline_, set);
  cmd.pushConstants(integrate_pipeline_, &push, sizeof(push));
  const std::uint32_t groups_x = std::min(touched, kMaxGroupsPerDimension);
  cmd.dispatch(groups_x, divideUp(touched, groups_x));
  cmd.barrier();
  cmd.writeTimestamp(timer_, 1);
  if (track_touched_) recordTouchedGather(cmd, touched);
  cmd.end();
  cmd.submitAndWait();
  stats.integrate_ms += timer_.elapsedMs(0, 1);
  if (track_touched_) readTouchedBlocks(touched);
}

void DeviceFusion::setTrackTouchedBlocks(bool on) {
  track_touched_ = on;
  last_touched_.clear();
  if (on && touched_keys_pipeline_.pipeline() == VK_NULL_HANDLE) {
    touched_keys_pipeline_ = vk::ComputePipeline::create(context_, "gather_touched_blocks", 4, 0);
  }
}

void DeviceFusion::recordTouchedGather(vk::CommandBuffer& cmd, std::uint32_t touched) {
  const std::uint64_t bytes = std::uint64_t{touched} * 8;
  if (!touched_keys_.valid() || touched_keys_.size() < bytes) {
    touched_keys_ = vk::Buffer::create(context_, std::max<std::uint64_t>(bytes * 3 / 2, 4096),
                                       vk::MemoryUsage::kHostReadback, "touched block keys");
  }
  // A member: the set must outlive the submission, which runIntegration makes after this returns.
  touched_keys_set_ = vk::DescriptorSet::create(
      context_, touched_keys_pipeline_,
      {&map_.hashEntries(), &touched_, &map_.counters(), &touched_keys_});
  cmd.bind(touched_keys_pipeline_, touched_keys_set_);
  const std::uint32_t groups = divideUp(touched, 256);
  const std::uint32_t groups_x = std::min(groups, kMaxGroupsPerDimension);
  cmd.dispatch(groups_x, divideUp(groups, groups_x));
  cmd.barrier();
}

void DeviceFusion::readTouchedBlocks(std::uint32_t touched) {
  const auto* keys = static_cast<const std::uint64_t*>(touched_keys_.mapped());
  last_touched_.resize(touched);
  for (std::uint32_t i = 0; i < touched; ++i) last_touched_[i] = unpackBlockKey(keys[i]);
}

}  // namespace strata
