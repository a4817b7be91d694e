// DeviceChange: recording of the passes (one dispatch each, a full barrier after each).
#include <vector>

#include "strata/core/error.h"
#include "strata/change/internal/change_device_internal.h"
#include "strata/change/change_rules.h"

namespace strata::change {

void DeviceChange::warmUp() {
  ensureBuffers(1, kCountersPerClean);
  Pipelines& p = pipelines(false);
  const vk::ComputePipeline* all[] = {&neighbours_,     &p.difference, &p.session_dynamic,
                                      &p.static_update, &p.erode,      &p.dilate};
  std::vector<vk::DescriptorSet> sets;
  // No blocks, no voxels, no entries (the voxel push is the largest).
  static_assert(sizeof(gpu::ChangeMorphPush) <= sizeof(gpu::ChangeVoxelPush) &&
                sizeof(gpu::ChangeNeighboursPush) <= sizeof(gpu::ChangeVoxelPush));
  const std::uint8_t zeros[sizeof(gpu::ChangeVoxelPush)] = {};
  vk::CommandBuffer cmd = vk::CommandBuffer::create(context_);
  cmd.begin();
  for (const vk::ComputePipeline* pipeline : all) {
    // Any storage buffer will do: with no work, no invocation touches memory.
    sets.push_back(vk::DescriptorSet::create(
        context_, *pipeline,
        std::vector<const vk::Buffer*>(pipeline->storageBufferCount(), &counters_)));
    cmd.bind(*pipeline, sets.back());
    cmd.pushConstants(*pipeline, zeros, pipeline->pushConstantBytes());
    cmd.dispatch(1);
    cmd.barrier();
  }
  cmd.end();
  cmd.submitAndWait();
}

void DeviceChange::recordNeighbours(vk::CommandBuffer& cmd) {
  sets_.push_back(
      vk::DescriptorSet::create(context_, neighbours_, {&map_.hashEntries(), &neighbour_slots_}));
  gpu::ChangeNeighboursPush push{};
  push.entry_count = map_.hashCapacity();
  push.hash_mask = map_.hashMask();
  push.slot_count = map_.blockCount();
  cmd.bind(neighbours_, sets_.back());
  cmd.pushConstants(neighbours_, &push, sizeof(push));
  dispatchLinear(cmd, divideUp(push.entry_count, 64));
  cmd.barrier();
}

void DeviceChange::recordVoxelPass(vk::CommandBuffer& cmd, const vk::ComputePipeline& pipeline,
                                   int s_layer, int m_layer, int label_layer,
                                   std::uint32_t counter) {
  sets_.push_back(vk::DescriptorSet::create(context_, pipeline,
                                            {&counters_, &map_.pool(s_layer), &map_.pool(m_layer),
                                             &map_.labelPool(label_layer), &raw_mask_}));
  gpu::ChangeVoxelPush push{};
  push.static_address = map_.poolAddress(s_layer);
  push.session_address = map_.poolAddress(m_layer);
  push.label_address = map_.labelPoolAddress(label_layer);
  push.voxel_count = map_.blockCount() * static_cast<std::uint32_t>(kVoxelsPerBlock);
  push.counter_index = counter;
  push.min_weight = config_.min_weight;
  push.threshold_m = config_.difference_threshold_m;
  push.merge_close_m = config_.merge_close_m;
  push.max_weight = map_.config().max_weight;
  cmd.bind(pipeline, sets_.back());
  cmd.pushConstants(pipeline, &push, sizeof(push));
  dispatchLinear(cmd, divideUp(push.voxel_count, 4 * 256));  // 4 voxels per invocation
  cmd.barrier();
}

void DeviceChange::recordRawPass(vk::CommandBuffer& cmd, const vk::ComputePipeline& pipeline,
                                 int s_layer, int m_layer, int raw_layer, std::uint32_t counter) {
  // The pass only sets the bits of dynamic voxels.
  cmd.fill(raw_mask_, 0u, 0, std::uint64_t{map_.blockCount()} * kRowsPerBlock * 4);
  cmd.barrier();
  recordVoxelPass(cmd, pipeline, s_layer, m_layer, raw_layer, counter);
}

void DeviceChange::recordErosion(vk::CommandBuffer& cmd, Pipelines& p, std::uint32_t counter) {
  cmd.fill(near_dynamic_, 0u, 0, std::uint64_t{map_.blockCount()} * 4);  // set where kept
  cmd.barrier();
  sets_.push_back(vk::DescriptorSet::create(
      context_, p.erode,
      {&counters_, &neighbour_slots_, &raw_mask_, &eroded_mask_, &near_dynamic_}));
  gpu::ChangeMorphPush push{};
  push.block_count = map_.blockCount();
  push.counter_index = counter;
  cmd.bind(p.erode, sets_.back());
  cmd.pushConstants(p.erode, &push, sizeof(push));
  dispatchLinear(cmd, divideUp(push.block_count, kBlocksPerMorphGroup));
  cmd.barrier();
}

void DeviceChange::recordDilation(vk::CommandBuffer& cmd, Pipelines& p, int raw, int out,
                                  std::uint32_t mask, std::uint32_t counter) {
  sets_.push_back(
      vk::DescriptorSet::create(context_, p.dilate,
                                {&counters_, &neighbour_slots_, &eroded_mask_, &map_.labelPool(raw),
                                 &map_.labelPool(out), &near_dynamic_}));
  gpu::ChangeMorphPush push{};
  push.raw_address = map_.labelPoolAddress(raw);
  push.out_address = map_.labelPoolAddress(out);
  push.block_count = map_.blockCount();
  push.mask = mask;
  push.counter_index = counter;
  cmd.bind(p.dilate, sets_.back());
  cmd.pushConstants(p.dilate, &push, sizeof(push));
  dispatchLinear(cmd, divideUp(push.block_count, kBlocksPerMorphGroup));
  cmd.barrier();
}

void DeviceChange::recordMerge(vk::CommandBuffer& cmd, const ChangeLayers& layers, Pipelines& p) {
  recordRawPass(cmd, p.difference, layers.static_tsdf, layers.session_tsdf, layers.raw_scratch, 0);
  cmd.writeTimestamp(timer_, kDifference);
  recordErosion(cmd, p, 1);
  cmd.writeTimestamp(timer_, kErosion);
  recordDilation(cmd, p, layers.raw_scratch, layers.labels,
                 static_cast<std::uint32_t>(DilationMask::kObserved), 2);
  cmd.writeTimestamp(timer_, kDilation);
  recordVoxelPass(cmd, p.static_update, layers.static_tsdf, layers.session_tsdf, layers.labels, 0);
  cmd.writeTimestamp(timer_, kStaticUpdate);
}

/// Raw session labels, erosion and dilation (restricted to raw dynamic voxels) per part.
void DeviceChange::recordParts(vk::CommandBuffer& cmd, const ChangeLayers& layers, Pipelines& p) {
  const auto mask = static_cast<std::uint32_t>(DilationMask::kRawDynamic);
  for (std::size_t i = 0; i < layers.session_parts.size(); ++i) {
    const auto [tsdf_layer, label_layer] = layers.session_parts[i];
    const auto first = static_cast<std::uint32_t>(kCountersPerClean * (1 + i));
    recordRawPass(cmd, p.session_dynamic, layers.static_tsdf, tsdf_layer, layers.raw_scratch,
                  first);
    recordErosion(cmd, p, first + 1);
    recordDilation(cmd, p, layers.raw_scratch, label_layer, mask, first + 2);
  }
  cmd.writeTimestamp(timer_, kSessionParts);
}

}  // namespace strata::change
