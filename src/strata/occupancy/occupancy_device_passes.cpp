// DeviceOccupancy's command recording (occupancy_device.h): one submission per pass, each timed
// with timestamp queries.
#include <algorithm>
#include <cstring>

#include "strata/occupancy/occupancy_device.h"
#include "strata/vk/dispatch_size.h"

namespace strata {
namespace {

using vk::kMaxGroupsPerDimension;

using vk::divideUp;

}  // namespace

gpu::MapCounters DeviceOccupancy::runAllocation(const gpu::OccupancyRayPush& push, bool upload,
                                                OccupancyFrameStats& stats) {
  vk::Context& context = map_.context();
  vk::DescriptorSet set = vk::DescriptorSet::create(
      context, allocate_pipeline_, {&map_.hashEntries(), &map_.counters(), &depth_});
  std::uint32_t groups_x = 0, groups_y = 0;
  rayGroups(groups_x, groups_y);
  vk::CommandBuffer cmd = vk::CommandBuffer::create(context);
  cmd.begin();
  cmd.resetQueries(timer_);
  cmd.writeTimestamp(timer_, 0);
  if (upload) {
    cmd.copy(depth_staging_, depth_, static_cast<VkDeviceSize>(width_px_) * height_px_ * 4);
  }
  cmd.fill(map_.counters(), 0u, offsetof(gpu::MapCounters, hash_failures), 4);
  cmd.barrier();
  cmd.writeTimestamp(timer_, 1);
  cmd.bind(allocate_pipeline_, set);
  cmd.pushConstants(allocate_pipeline_, &push, sizeof(push));
  cmd.dispatch(groups_x, groups_y);
  cmd.barrier();
  cmd.writeTimestamp(timer_, 2);
  cmd.copy(map_.counters(), readback_, sizeof(gpu::MapCounters));
  cmd.barrier();
  cmd.end();
  cmd.submitAndWait();
  if (upload) stats.upload_ms += timer_.elapsedMs(0, 1);
  stats.allocate_ms += timer_.elapsedMs(1, 2);
  stats.allocation_passes += 1;
  gpu::MapCounters counters{};
  std::memcpy(&counters, readback_.mapped(), sizeof(counters));
  return counters;
}

void DeviceOccupancy::ensureSlotBuffers() {
  const std::uint32_t capacity = map_.blockCapacity();
  if (capacity <= slot_capacity_) return;
  vk::Context& context = map_.context();
  const std::uint64_t bytes = std::uint64_t{capacity} * 4;
  block_stamps_ =
      vk::Buffer::create(context, bytes, vk::MemoryUsage::kDeviceLocal, "occupancy block stamps");
  // A list entry per slot at most: the mark pass lists each block once per frame.
  touched_slots_ =
      vk::Buffer::create(context, bytes, vk::MemoryUsage::kDeviceLocal, "occupancy touched slots");
  vk::CommandBuffer cmd = vk::CommandBuffer::create(context);
  cmd.begin();
  cmd.fill(block_stamps_, 0u);  // frame ids start at 1
  cmd.barrier();
  cmd.end();
  cmd.submitAndWait();
  slot_capacity_ = capacity;
}

gpu::OccupancyCounters DeviceOccupancy::runMark(const gpu::OccupancyRayPush& push,
                                                OccupancyFrameStats& stats) {
  vk::Context& context = map_.context();
  const vk::Buffer& state = map_.labelPool(state_layer_);
  const bool by_address = state.size() > context.limits().max_storage_buffer_range_bytes;
  if (by_address && mark_by_address_pipeline_.pipeline() == VK_NULL_HANDLE) {
    mark_by_address_pipeline_ = vk::ComputePipeline::create(context, "occupancy_mark", 6,
                                                            sizeof(gpu::OccupancyRayPush), {1u});
  }
  const vk::ComputePipeline& pipeline = by_address ? mark_by_address_pipeline_ : mark_pipeline_;
  vk::DescriptorSet set = vk::DescriptorSet::create(
      context, pipeline,
      {&map_.hashEntries(), &counters_, &depth_, &block_stamps_, &touched_slots_, &state});
  std::uint32_t groups_x = 0, groups_y = 0;
  rayGroups(groups_x, groups_y);
  vk::CommandBuffer cmd = vk::CommandBuffer::create(context);
  cmd.begin();
  cmd.resetQueries(timer_);
  cmd.fill(counters_, 0u);
  cmd.barrier();
  cmd.writeTimestamp(timer_, 0);
  cmd.bind(pipeline, set);
  cmd.pushConstants(pipeline, &push, sizeof(push));
  cmd.dispatch(groups_x, groups_y);
  cmd.barrier();
  cmd.writeTimestamp(timer_, 1);
  cmd.copy(counters_, readback_, sizeof(gpu::OccupancyCounters));
  cmd.barrier();
  cmd.end();
  cmd.submitAndWait();
  stats.mark_ms += timer_.elapsedMs(0, 1);
  gpu::OccupancyCounters counters{};
  std::memcpy(&counters, readback_.mapped(), sizeof(counters));
  return counters;
}

void DeviceOccupancy::runUpdate(std::uint32_t touched, OccupancyFrameStats& stats) {
  const OccupancyLogOdds l = config_.logOdds();
  gpu::OccupancyUpdatePush push{};
  push.state_address = map_.labelPoolAddress(state_layer_);
  push.log_odds_address = map_.labelPoolAddress(log_odds_layer_);
  push.l_hit = l.hit;
  push.l_miss = l.miss;
  push.l_min = l.min;
  push.l_max = l.max;
  push.touched_count = touched;
  vk::DescriptorSet set =
      vk::DescriptorSet::create(map_.context(), update_pipeline_, {&touched_slots_});
  vk::CommandBuffer cmd = vk::CommandBuffer::create(map_.context());
  cmd.begin();
  cmd.resetQueries(timer_);
  cmd.writeTimestamp(timer_, 0);
  cmd.bind(update_pipeline_, set);
  cmd.pushConstants(update_pipeline_, &push, sizeof(push));
  const std::uint32_t groups_x = std::min(touched, kMaxGroupsPerDimension);
  cmd.dispatch(groups_x, divideUp(touched, kMaxGroupsPerDimension));
  cmd.barrier();
  cmd.writeTimestamp(timer_, 1);
  cmd.end();
  cmd.submitAndWait();
  stats.update_ms += timer_.elapsedMs(0, 1);
}

}  // namespace strata
