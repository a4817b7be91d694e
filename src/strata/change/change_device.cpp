#include "strata/change/change_device.h"

#include <chrono>
#include <cstring>
#include <string>

#include "strata/core/clock.h"
#include "strata/core/error.h"
#include "strata/change/internal/change_device_internal.h"

namespace strata::change {
namespace {

const ChangeConfig& validated(const ChangeConfig& config, float voxel_size_m) {
  config.validate(voxel_size_m);
  return config;
}

/// A device-local buffer of at least `bytes` (grown by half again, so growth is rare).
void ensureSize(vk::Context& context, vk::Buffer& buffer, std::uint64_t bytes, const char* name) {
  if (buffer.valid() && buffer.size() >= bytes) return;
  if (bytes > context.limits().max_storage_buffer_range_bytes) {
    throw DeviceError(std::string("change detection: the ") + name + " of " +
                      std::to_string(bytes >> 20) + " MiB exceeds one storage binding on " +
                      context.deviceName() + "; use a larger voxel size");
  }
  buffer = vk::Buffer::create(context, std::max<std::uint64_t>(bytes * 3 / 2, 4096),
                              vk::MemoryUsage::kDeviceLocal, name);
}

}  // namespace

DeviceChange::DeviceChange(vk::Context& context, DeviceTsdfMap& map, const ChangeConfig& config)
    : context_(context),
      map_(map),
      config_(validated(config, map.config().voxel_size_m)),
      neighbours_(vk::ComputePipeline::create(context, "change_block_neighbours", 2,
                                              sizeof(gpu::ChangeNeighboursPush))),
      timer_(vk::TimestampQueries::create(context, kStamps)) {
  warmUp();
}

DeviceChange::~DeviceChange() = default;

DeviceChange::Pipelines& DeviceChange::pipelines(bool by_address) {
  std::unique_ptr<Pipelines>& p = pipelines_[by_address ? 1 : 0];
  if (!p) p = std::make_unique<Pipelines>(context_, config_, by_address);
  return *p;
}

void DeviceChange::setBindingLimit(std::uint64_t bytes) { binding_limit_bytes_ = bytes; }

void DeviceChange::ensureBuffers(std::uint32_t blocks, std::uint32_t counters) {
  const std::uint64_t mask_bytes = std::uint64_t{blocks} * kRowsPerBlock * 4;
  ensureSize(context_, neighbour_slots_, std::uint64_t{blocks} * kNeighbours * 4,
             "neighbour table");
  ensureSize(context_, raw_mask_, mask_bytes, "raw row masks");
  ensureSize(context_, eroded_mask_, mask_bytes, "eroded row masks");
  ensureSize(context_, near_dynamic_, std::uint64_t{blocks} * 4, "near-dynamic flags");
  const std::uint64_t counter_bytes = std::uint64_t{counters} * sizeof(std::uint32_t);
  if (!counters_.valid() || counters_.size() < counter_bytes) {
    counters_ = vk::Buffer::create(context_, counter_bytes, vk::MemoryUsage::kDeviceLocal,
                                   "change counters");
    counters_readback_ = vk::Buffer::create(context_, counter_bytes, vk::MemoryUsage::kHostReadback,
                                            "change counters readback");
  }
}

void DeviceChange::run(const ChangeLayers& layers, bool merge) {
  const auto counter_count =
      static_cast<std::uint32_t>(kCountersPerClean * (1 + layers.session_parts.size()));
  ensureBuffers(map_.blockCount(), counter_count);
  // Every TSDF layer has the same size, and so has every label layer.
  const std::uint64_t range =
      std::min(binding_limit_bytes_, context_.limits().max_storage_buffer_range_bytes);
  Pipelines& p = pipelines(map_.pool(layers.static_tsdf).size() > range ||
                           map_.labelPool(layers.raw_scratch).size() > range);
  sets_.clear();
  vk::CommandBuffer cmd = vk::CommandBuffer::create(context_);
  cmd.begin();
  cmd.resetQueries(timer_);
  cmd.fill(counters_, 0u);
  cmd.barrier();
  cmd.writeTimestamp(timer_, kStart);
  recordNeighbours(cmd);
  cmd.writeTimestamp(timer_, kNeighbourTable);
  if (merge) {
    recordMerge(cmd, layers, p);
  } else {
    for (std::uint32_t stamp = kDifference; stamp <= kStaticUpdate; ++stamp) {
      cmd.writeTimestamp(timer_, stamp);  // stages not run: zero time
    }
  }
  recordParts(cmd, layers, p);
  cmd.copy(counters_, counters_readback_, std::uint64_t{counter_count} * sizeof(std::uint32_t));
  cmd.barrier();
  cmd.end();
  cmd.submitAndWait();
  sets_.clear();  // done with: the map may replace the buffers they name before the next run
  counts_.resize(counter_count);
  std::memcpy(counts_.data(), counters_readback_.mapped(), counts_.size() * sizeof(std::uint32_t));
}

ChangeUpdateStats DeviceChange::update(const ChangeLayers& layers) {
  const auto wall_start = std::chrono::steady_clock::now();
  ChangeUpdateStats stats;
  stats.blocks = map_.blockCount();
  stats.voxels = std::uint64_t{stats.blocks} * kVoxelsPerBlock;
  if (stats.blocks == 0) return stats;
  run(layers, true);
  ChangeStageTimes& t = stats.stages;
  t.neighbours_ms = timer_.elapsedMs(kStart, kNeighbourTable);
  t.difference_ms = timer_.elapsedMs(kNeighbourTable, kDifference);
  t.erosion_ms = timer_.elapsedMs(kDifference, kErosion);
  t.dilation_ms = timer_.elapsedMs(kErosion, kDilation);
  t.static_update_ms = timer_.elapsedMs(kDilation, kStaticUpdate);
  t.session_dynamic_ms = timer_.elapsedMs(kStaticUpdate, kSessionParts);
  stats.raw_dynamic_voxels = counts_[0];
  stats.eroded_dynamic_voxels = counts_[1];
  stats.dynamic_voxels = counts_[2];
  for (std::size_t i = 0; i < layers.session_parts.size(); ++i) {
    stats.session_dynamic_voxels += counts_[kCountersPerClean * (1 + i) + 2];
  }
  stats.wall_ms =
      msSince(wall_start);
  return stats;
}

DynamicPartStats DeviceChange::dynamicParts(const ChangeLayers& layers) {
  DynamicPartStats stats;
  stats.dynamic_voxels.assign(layers.session_parts.size(), 0);
  if (map_.blockCount() == 0 || layers.session_parts.empty()) return stats;
  run(layers, false);
  stats.device_ms = timer_.elapsedMs(kStart, kSessionParts);
  for (std::size_t i = 0; i < layers.session_parts.size(); ++i) {
    stats.dynamic_voxels[i] = counts_[kCountersPerClean * (1 + i) + 2];
  }
  return stats;
}

LabelMap downloadLabels(DeviceTsdfMap& map, int label_layer) {
  LabelMap out;
  out.voxel_size_m = map.config().voxel_size_m;
  const std::uint32_t count = map.blockCount();
  std::vector<std::uint32_t> labels(std::size_t{count} * kVoxelsPerBlock);
  if (count > 0) {
    vk::download(map.context(), map.labelPool(label_layer), labels.data(),
                 labels.size() * sizeof(std::uint32_t));
  }
  for (const auto& [index, slot] : map.blockSlots()) {
    if (slot >= count) continue;  // not a committed block (cannot happen after a full frame)
    LabelBlock& block = out.allocateBlock(index);
    const std::uint32_t* source = &labels[std::size_t{slot} * kVoxelsPerBlock];
    for (int v = 0; v < kVoxelsPerBlock; ++v) block[v] = static_cast<VoxelLabel>(source[v]);
  }
  return out;
}

}  // namespace strata::change
