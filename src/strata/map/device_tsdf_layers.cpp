// DeviceTsdfMap's layers (device_tsdf_map.h): more TSDF and label pools that follow the same slots;
// partial downloads.
#include <algorithm>
#include <string>
#include <unordered_map>

#include "strata/core/error.h"
#include "strata/map/device_tsdf_map.h"

namespace strata {
namespace {

void fillZero(vk::Context& context, vk::Buffer& layer) {
  vk::CommandBuffer cmd = vk::CommandBuffer::create(context);
  cmd.begin();
  cmd.fill(layer, 0u);  // unobserved / label 0
  cmd.barrier();
  cmd.end();
  cmd.submitAndWait();
}

}  // namespace

vk::Buffer DeviceTsdfMap::makeLayer(std::uint64_t blocks, std::uint64_t block_bytes,
                                    const std::string& name, bool zero) {
  vk::Buffer layer =
      vk::Buffer::create(context_, blocks * block_bytes, vk::MemoryUsage::kDeviceLocal, name);
  if (zero) fillZero(context_, layer);
  return layer;
}

void DeviceTsdfMap::clearTsdfLayer(int layer) { fillZero(context_, tsdfLayer(layer)); }
void DeviceTsdfMap::clearLabelLayer(int layer) { fillZero(context_, labelLayer(layer)); }

std::vector<std::pair<BlockIndex, std::uint32_t>> DeviceTsdfMap::blockSlots() {
  std::vector<std::pair<BlockIndex, std::uint32_t>> out;
  for (const auto& [key, slot] : readTable()) out.emplace_back(unpackBlockKey(key), slot);
  return out;
}

void DeviceTsdfMap::zeroLayers(std::uint32_t first_block_0, std::uint32_t first_block) {
  vk::CommandBuffer cmd = vk::CommandBuffer::create(context_);
  cmd.begin();
  auto zero = [&](vk::Buffer& layer, std::uint32_t first, std::uint64_t block_bytes) {
    const std::uint64_t from = std::uint64_t{first} * block_bytes;
    if (from < layer.size()) cmd.fill(layer, 0u, from, layer.size() - from);
  };
  for (std::size_t i = 0; i < tsdf_layers_.size(); ++i) {
    zero(tsdf_layers_[i], i == 0 ? first_block_0 : first_block, kBlockBytes);
  }
  for (vk::Buffer& layer : label_layers_) zero(layer, first_block, kLabelBlockBytes);
  cmd.barrier();
  cmd.end();
  cmd.submitAndWait();
}

void DeviceTsdfMap::uploadLayer(const TsdfMap& map, int layer) {
  tsdfLayer(layer);  // throws InputError for a layer the map lacks, before anything changes
  KeySlots key_slots = readTable();
  std::unordered_map<std::uint64_t, std::uint32_t> slot_of(key_slots.begin(), key_slots.end());
  std::uint32_t count = block_count_;
  for (const BlockIndex& b : map.sortedBlockIndices()) {
    const std::uint64_t key = packBlockKey(b);
    if (slot_of.emplace(key, count).second) key_slots.emplace_back(key, count++);
  }
  if (count > block_capacity_) growPool(count);  // keeps slots [0, block_count_) of every layer
  if (count != block_count_) {
    writeTable(key_slots, std::max(hash_capacity_, count * 2 + 1));  // rounded up to 2^n
    block_count_ = count;
    writeCounters();
  }
  // The whole layer is written, so blocks that map lacks become unobserved here.
  std::vector<TsdfBlock> blocks(count);
  for (TsdfBlock& block : blocks) block.fill(TsdfVoxel{});
  for (const auto& [index, block] : map.blocks()) blocks[slot_of.at(packBlockKey(index))] = block;
  // Looked up only now: growing the pool replaced every layer's buffer.
  if (count > 0) vk::upload(context_, tsdfLayer(layer), blocks.data(), blocks.size() * kBlockBytes);
}

int DeviceTsdfMap::addTsdfLayer() {
  tsdf_layers_.push_back(makeLayer(block_capacity_, kBlockBytes, "TSDF voxel pool", true));
  return tsdfLayerCount() - 1;
}

int DeviceTsdfMap::addLabelLayer() {
  label_layers_.push_back(makeLayer(block_capacity_, kLabelBlockBytes, "label pool", true));
  return labelLayerCount() - 1;
}

std::uint64_t DeviceTsdfMap::deviceBytes() const {
  std::uint64_t bytes = entries_.size() + counters_.size();
  for (const vk::Buffer& b : tsdf_layers_) bytes += b.size();
  for (const vk::Buffer& b : label_layers_) bytes += b.size();
  return bytes;
}

namespace {

template <typename Layers>
auto& layerAt(Layers& layers, int layer, const char* what) {
  if (layer < 0 || layer >= static_cast<int>(layers.size())) {
    throw InputError(std::string(what) + " layer " + std::to_string(layer) +
                     " does not exist (the map has " + std::to_string(layers.size()) + ")");
  }
  return layers[static_cast<std::size_t>(layer)];
}

}  // namespace

vk::Buffer& DeviceTsdfMap::tsdfLayer(int layer) { return layerAt(tsdf_layers_, layer, "TSDF"); }
const vk::Buffer& DeviceTsdfMap::tsdfLayer(int layer) const {
  return layerAt(tsdf_layers_, layer, "TSDF");
}
vk::Buffer& DeviceTsdfMap::labelLayer(int layer) { return layerAt(label_layers_, layer, "label"); }
const vk::Buffer& DeviceTsdfMap::labelLayer(int layer) const {
  return layerAt(label_layers_, layer, "label");
}

void DeviceTsdfMap::downloadBlocks(const std::vector<BlockIndex>& blocks, TsdfMap& out,
                                   int layer) {
  const vk::Buffer& pool = tsdfLayer(layer);
  if (out.config().voxel_size_m != config_.voxel_size_m) {
    throw InputError("downloadBlocks: the host map's voxel size differs from the device map's");
  }
  std::unordered_map<std::uint64_t, std::uint32_t> slot_of;
  for (const auto& [key, slot] : readTable()) slot_of.emplace(key, slot);
  std::vector<std::pair<std::uint32_t, BlockIndex>> wanted;  // (slot, block), by slot
  for (const BlockIndex& b : blocks) {
    const auto it = slot_of.find(packBlockKey(b));
    if (it != slot_of.end() && it->second < block_count_) wanted.emplace_back(it->second, b);
  }
  std::sort(wanted.begin(), wanted.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  wanted.erase(std::unique(wanted.begin(), wanted.end(),
                           [](const auto& a, const auto& b) { return a.first == b.first; }),
               wanted.end());
  // One copy per run of consecutive slots (blocks allocated together sit together).
  std::vector<TsdfBlock> run;
  for (std::size_t i = 0; i < wanted.size();) {
    std::size_t end = i + 1;
    while (end < wanted.size() && wanted[end].first == wanted[end - 1].first + 1) ++end;
    run.resize(end - i);
    vk::download(context_, pool, run.data(), run.size() * kBlockBytes,
                 wanted[i].first * kBlockBytes);
    for (std::size_t k = i; k < end; ++k) out.allocateBlock(wanted[k].second) = run[k - i];
    i = end;
  }
}

}  // namespace strata
