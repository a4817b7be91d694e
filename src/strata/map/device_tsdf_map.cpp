#include "strata/map/device_tsdf_map.h"

#include <algorithm>
#include <cstring>
#include <sstream>
#include <unordered_map>

#include "strata/core/error.h"
#include "strata/map/device_layout.h"

namespace strata {
namespace {

// One binding sees at most 128 MiB on lavapipe; 2^23 entries of 16 bytes is exactly that.
constexpr std::uint32_t kMaxHashCapacity = 1u << 23;
constexpr std::uint32_t kMaxProbes = 128;  // matches kMaxHashProbes in map_layout.glsl

std::uint32_t nextPowerOfTwo(std::uint32_t v) {
  std::uint32_t p = 1;
  while (p < v) p <<= 1;
  return p;
}

/// Host-side build of a table; false when some key needed more than kMaxProbes probes.
bool buildTable(const std::vector<std::pair<std::uint64_t, std::uint32_t>>& key_slots,
                std::uint32_t capacity, std::vector<gpu::HashEntry>& table) {
  table.assign(capacity, gpu::HashEntry{kEmptyBlockKey, ~0u, ~0u});
  const std::uint32_t mask = capacity - 1;
  for (const auto& [key, slot] : key_slots) {
    std::uint32_t e = hashBlockKey(key) & mask;
    std::uint32_t probe = 0;
    while (table[e].key != kEmptyBlockKey && probe < kMaxProbes) {
      e = (e + 1) & mask;
      ++probe;
    }
    if (probe == kMaxProbes) return false;
    table[e].key = key;
    table[e].slot = slot;
  }
  return true;
}

}  // namespace

DeviceTsdfMap::DeviceTsdfMap(vk::Context& context, const MapConfig& config)
    : context_(context), config_(config) {
  config_.validate();
  writeTable({}, config_.initial_hash_capacity);
  growPool(config_.max_block_capacity > 0
               ? std::min(config_.initial_block_capacity, config_.max_block_capacity)
               : config_.initial_block_capacity);
  writeCounters();
}

void DeviceTsdfMap::writeCounters() {
  if (!counters_.valid()) {
    counters_ = vk::Buffer::create(context_, sizeof(gpu::MapCounters), vk::MemoryUsage::kDeviceLocal,
                                   "map counters");
  }
  const gpu::MapCounters counters{block_count_, 0, 0, 0};
  vk::upload(context_, counters_, &counters, sizeof(counters));
}

DeviceTsdfMap::KeySlots DeviceTsdfMap::readTable() {
  std::vector<gpu::HashEntry> table(hash_capacity_);
  vk::download(context_, entries_, table.data(), table.size() * sizeof(gpu::HashEntry));
  KeySlots key_slots;
  key_slots.reserve(block_count_);
  for (const gpu::HashEntry& entry : table) {
    if (entry.key != kEmptyBlockKey) key_slots.emplace_back(entry.key, entry.slot);
  }
  return key_slots;
}

void DeviceTsdfMap::writeTable(const KeySlots& key_slots, std::uint32_t capacity) {
  std::vector<gpu::HashEntry> table;
  capacity = nextPowerOfTwo(std::max<std::uint32_t>(capacity, 64));
  while (!buildTable(key_slots, capacity, table)) {
    if (capacity >= kMaxHashCapacity) break;
    capacity *= 2;
  }
  if (capacity > kMaxHashCapacity || table.size() != capacity) {
    std::ostringstream msg;
    msg << "block hash table full: " << key_slots.size() << " blocks need more than "
        << kMaxHashCapacity << " entries; use a larger voxel size or a smaller depth range";
    throw DeviceError(msg.str());
  }
  const std::size_t bytes = table.size() * sizeof(gpu::HashEntry);
  if (entries_.valid() && entries_.size() == bytes) {
    // NOTE: in place, so rolling a refused frame back allocates nothing (forgetBlocksFrom).
    vk::upload(context_, entries_, table.data(), bytes);
  } else {
    // A new buffer is filled before it replaces the old one: a failure keeps the old table.
    vk::Buffer entries =
        vk::Buffer::create(context_, bytes, vk::MemoryUsage::kDeviceLocal, "block hash table");
    vk::upload(context_, entries, table.data(), bytes);
    entries_ = std::move(entries);
  }
  hash_capacity_ = capacity;
}

void DeviceTsdfMap::growHash(std::uint32_t min_capacity) {
  if (min_capacity > kMaxHashCapacity) {
    std::ostringstream msg;
    msg << "block hash table full: " << block_count_ << " blocks were asked for and the table "
        << "cannot exceed " << kMaxHashCapacity << " entries on this device";
    throw DeviceError(msg.str());
  }
  writeTable(readTable(), nextPowerOfTwo(min_capacity));
}

void DeviceTsdfMap::maintainLoadFactor() {
  if (static_cast<std::uint64_t>(block_count_) * 2 > hash_capacity_ &&
      hash_capacity_ < kMaxHashCapacity) {
    growHash(hash_capacity_ * 2);
  }
}

std::uint64_t DeviceTsdfMap::deviceMaxBlocks() const {
  return context_.limits().max_memory_allocation_bytes / kBlockBytes;
}

std::uint64_t DeviceTsdfMap::maxBlocks() const {
  const std::uint64_t device_max = deviceMaxBlocks();
  return config_.max_block_capacity > 0
             ? std::min<std::uint64_t>(device_max, config_.max_block_capacity)
             : device_max;
}

void DeviceTsdfMap::reserveBlocks(std::uint32_t blocks) {
  const auto wanted = static_cast<std::uint32_t>(std::min<std::uint64_t>(blocks, maxBlocks()));
  if (wanted <= block_capacity_) return;
  try {
    growPool(wanted);
  } catch (const DeviceError&) {
    // Headroom only: the map is as it was, and a frame that truly needs the blocks reports it.
  }
}

void DeviceTsdfMap::growPool(std::uint32_t min_blocks) {
  const std::uint64_t device_max = deviceMaxBlocks();
  const std::uint64_t max_blocks = maxBlocks();
  if (min_blocks > max_blocks) {
    std::ostringstream msg;
    msg << "TSDF pool full: " << min_blocks << " blocks were asked for but "
        << (max_blocks < device_max ? "the map's block budget (max_block_capacity)"
                                    : "one allocation on " + context_.deviceName())
        << " holds at most " << max_blocks << " blocks (" << (max_blocks * kBlockBytes >> 20)
        << " MiB); use a larger voxel size, a shorter depth range or fewer frames";
    throw DeviceError(msg.str());
  }
  const std::uint64_t wanted = std::max<std::uint64_t>(
      min_blocks, std::min<std::uint64_t>(max_blocks, std::uint64_t{block_capacity_} * 2));
  // Every layer is allocated before any is replaced, so a failure leaves the map as it was.
  std::vector<vk::Buffer> tsdf(std::max<std::size_t>(tsdf_layers_.size(), 1));
  std::vector<vk::Buffer> labels(label_layers_.size());
  try {
    for (vk::Buffer& b : tsdf) b = makeLayer(wanted, kBlockBytes, "TSDF voxel pool", false);
    for (vk::Buffer& b : labels) b = makeLayer(wanted, kLabelBlockBytes, "label pool", false);
  } catch (const DeviceError& e) {
    std::ostringstream msg;
    msg << "TSDF pool full: growing " << tsdf.size() + labels.size() << " layer(s) to " << wanted
        << " blocks for the " << min_blocks << " blocks asked for failed (" << e.what() << ")";
    throw DeviceError(msg.str());
  }
  vk::CommandBuffer cmd = vk::CommandBuffer::create(context_);
  cmd.begin();
  auto copyLayer = [&](const vk::Buffer& from, vk::Buffer& to, std::uint64_t block_bytes) {
    const std::uint64_t used_bytes = std::uint64_t{block_count_} * block_bytes;
    if (used_bytes > 0) cmd.copy(from, to, used_bytes);
    cmd.fill(to, 0u, used_bytes, to.size() - used_bytes);  // new blocks start unobserved
  };
  if (tsdf_layers_.empty()) cmd.fill(tsdf[0], 0u);
  for (std::size_t i = 0; i < tsdf_layers_.size(); ++i) {
    copyLayer(tsdf_layers_[i], tsdf[i], kBlockBytes);
  }
  for (std::size_t i = 0; i < labels.size(); ++i) {
    copyLayer(label_layers_[i], labels[i], kLabelBlockBytes);
  }
  cmd.barrier();
  cmd.end();
  cmd.submitAndWait();
  tsdf_layers_ = std::move(tsdf);
  label_layers_ = std::move(labels);
  block_capacity_ = static_cast<std::uint32_t>(wanted);
}

void DeviceTsdfMap::commitBlockCount(std::uint32_t block_count) {
  if (block_count <= block_capacity_) {
    block_count_ = block_count;
    return;
  }
  try {
    growPool(block_count);
    block_count_ = block_count;
  } catch (const DeviceError&) {
    // The pass is refused whole: forget the blocks it allocated, keep everything fused so far.
    forgetBlocksFrom(block_count_);
    throw;
  }
}

void DeviceTsdfMap::forgetBlocksFrom(std::uint32_t block_count) {
  KeySlots key_slots = readTable();
  key_slots.erase(std::remove_if(key_slots.begin(), key_slots.end(),
                                 [&](const auto& ks) { return ks.second >= block_count; }),
                  key_slots.end());
  // Same capacity, so the table is rewritten in its own buffer: no allocation on a full device.
  writeTable(key_slots, hash_capacity_);
  block_count_ = block_count;
  writeCounters();
}

void DeviceTsdfMap::download(TsdfMap& out, int layer) {
  const vk::Buffer& pool = tsdfLayer(layer);
  out = TsdfMap(config_);
  const auto key_slots = readTable();
  std::vector<TsdfBlock> blocks(block_count_);
  if (block_count_ > 0) vk::download(context_, pool, blocks.data(), blocks.size() * kBlockBytes);
  for (const auto& [key, slot] : key_slots) {
    if (slot >= block_count_) {
      throw DeviceError("device map is inconsistent: a block has slot " + std::to_string(slot) +
                        " beyond the " + std::to_string(block_count_) + " allocated blocks");
    }
    out.allocateBlock(unpackBlockKey(key)) = blocks[slot];
  }
}

void DeviceTsdfMap::upload(const TsdfMap& map) {
  const std::vector<BlockIndex> indices = map.sortedBlockIndices();
  KeySlots key_slots;
  std::vector<TsdfBlock> blocks;
  key_slots.reserve(indices.size());
  blocks.reserve(indices.size());
  for (const BlockIndex& b : indices) {
    key_slots.emplace_back(packBlockKey(b), static_cast<std::uint32_t>(blocks.size()));
    blocks.push_back(*map.findBlock(b));
  }
  const auto count = static_cast<std::uint32_t>(blocks.size());
  block_count_ = 0;
  if (count > block_capacity_) growPool(count);
  writeTable(key_slots, std::max(config_.initial_hash_capacity, nextPowerOfTwo(count * 2 + 1)));
  if (count > 0) vk::upload(context_, tsdfLayer(0), blocks.data(), blocks.size() * kBlockBytes);
  // Slots past the uploaded blocks may hold an earlier map: clear them for future allocations;
  // the other layers describe no block of the new index.
  zeroLayers(count, 0);
  block_count_ = count;
  writeCounters();
}

}  // namespace strata
