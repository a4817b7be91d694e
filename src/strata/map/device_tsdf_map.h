#pragma once
// The block-sparse TSDF map on the device: an open-addressing hash table from block key to pool
// slot (kernels insert with 64-bit atomics), and the TSDF voxel pool addressed by device address.
// Both grow on demand; when the device cannot hold more, an error says how many blocks were asked
// for and the map stays as it was (new buffers are filled before they replace the old ones).
// Layers share the block index: TSDF layer 0 is the map every kernel uses by default; more TSDF
// layers (one per mapping session, a static estimate) and label layers (one uint32 per voxel) can
// be added. Every layer holds one block per slot and all grow together, so a block allocated for
// one layer exists (unobserved, label 0) in all the others.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "strata/map/map_config.h"
#include "strata/map/tsdf_map.h"
#include "strata/vk/vk.h"

namespace strata {

class DeviceTsdfMap {
 public:
  DeviceTsdfMap(vk::Context& context, const MapConfig& config);

  const MapConfig& config() const { return config_; }
  vk::Context& context() { return context_; }
  /// Blocks allocated (as of the last synchronisation with the device).
  std::uint32_t blockCount() const { return block_count_; }
  std::uint32_t blockCapacity() const { return block_capacity_; }
  std::uint32_t hashCapacity() const { return hash_capacity_; }
  std::uint32_t hashMask() const { return hash_capacity_ - 1; }
  std::uint64_t poolAddress(int layer = 0) const { return tsdfLayer(layer).deviceAddress(); }
  /// Pools of every layer, hash table and counters.
  std::uint64_t deviceBytes() const;
  /// Bytes of device memory per voxel of one TSDF layer (voxel payload only).
  static constexpr std::uint32_t kBytesPerVoxel = sizeof(TsdfVoxel);
  /// Bytes per voxel of a label layer.
  static constexpr std::uint32_t kLabelBytesPerVoxel = sizeof(std::uint32_t);
  /// Bytes per block of a TSDF layer and of a label layer (a slot's stride in each pool).
  static constexpr std::uint64_t kBlockBytes = sizeof(TsdfBlock);
  static constexpr std::uint64_t kLabelBlockBytes = std::uint64_t{kVoxelsPerBlock} * kLabelBytesPerVoxel;

  vk::Buffer& hashEntries() { return entries_; }
  vk::Buffer& counters() { return counters_; }
  /// TSDF layer `layer`: slot s holds TsdfVoxel[512] at s * 6144 bytes.
  vk::Buffer& pool(int layer = 0) { return tsdfLayer(layer); }

  int tsdfLayerCount() const { return static_cast<int>(tsdf_layers_.size()); }
  int labelLayerCount() const { return static_cast<int>(label_layers_.size()); }
  /// Adds a TSDF layer, every voxel unobserved; returns its index.
  int addTsdfLayer();
  /// Adds a label layer, every voxel 0; returns its index. Slot s holds uint32[512] at s * 2048.
  int addLabelLayer();
  vk::Buffer& labelPool(int layer) { return labelLayer(layer); }
  /// Every voxel of one TSDF layer unobserved / of one label layer 0 again, as when added (for
  /// reusing a layer instead of adding one). InputError for a layer the map lacks.
  void clearTsdfLayer(int layer);
  void clearLabelLayer(int layer);
  std::uint64_t labelPoolAddress(int layer) const { return labelLayer(layer).deviceAddress(); }
  /// Every allocated block with its slot (downloads the hash table).
  std::vector<std::pair<BlockIndex, std::uint32_t>> blockSlots();

  /// Record that the device handed out `block_count` slots. Grows the pool (device-side copy) when
  /// they exceed capacity; when the device or the block budget cannot hold them, forgets every
  /// block allocated since the last commit (forgetBlocksFrom) and throws DeviceError naming the
  /// number of blocks asked for and the limit (max_block_capacity, or the device's memory).
  void commitBlockCount(std::uint32_t block_count);
  /// Forgets the blocks at slots >= `block_count` (what a refused frame allocated; their voxels
  /// must never have been integrated), so the index is as it was at that count. Needs no device
  /// memory where buffers are host-visible (lavapipe, integrated GPUs): the table is rewritten in
  /// place; with staged memory it needs the context's staging buffers. Slots past the count keep
  /// zeros (unobserved) because nothing was integrated into them.
  void forgetBlocksFrom(std::uint32_t block_count);
  /// Rebuilds the hash table with at least `min_capacity` entries (power of two), keeping slots.
  void growHash(std::uint32_t min_capacity);
  /// Grow the table when it is more than half full, so probes stay short.
  void maintainLoadFactor();
  /// Grows the pool ahead of time so that it holds at least `blocks` blocks, as far as the map's
  /// block budget and the device allow (never throws for the budget: the frame that needs more
  /// then fails in commitBlockCount with the usual error). Lets a frame run in one submission.
  void reserveBlocks(std::uint32_t blocks);

  /// Explicit device->host copy of one TSDF layer (every allocated block, unobserved ones too).
  void download(TsdfMap& out, int layer = 0);
  /// Device->host copy of some blocks of one TSDF layer into `out` (a map of this config): each
  /// of `blocks` the device holds replaces out's copy; the others are left as they are. Costs the
  /// hash table plus the listed blocks (what changed since the last copy, for incremental meshes).
  void downloadBlocks(const std::vector<BlockIndex>& blocks, TsdfMap& out, int layer = 0);
  /// Replaces the device map with `map` (same config required): the block index becomes map's,
  /// TSDF layer 0 its voxels, every other layer unobserved / label 0.
  void upload(const TsdfMap& map);
  /// Replaces one TSDF layer with `map`, keeping the block index and the other layers: map's
  /// blocks missing from the index are allocated (unobserved in the other layers), allocated
  /// blocks that map lacks become unobserved in this layer.
  void uploadLayer(const TsdfMap& map, int layer);

 private:
  using KeySlots = std::vector<std::pair<std::uint64_t, std::uint32_t>>;
  KeySlots readTable();
  void writeTable(const KeySlots& key_slots, std::uint32_t capacity);
  void growPool(std::uint32_t min_blocks);
  /// Blocks one layer allocation on the device holds, and that capped by max_block_capacity.
  std::uint64_t deviceMaxBlocks() const;
  std::uint64_t maxBlocks() const;
  void writeCounters();
  /// Buffer of `blocks` blocks for a layer of `block_bytes` per block (zero-filled when `zero`).
  vk::Buffer makeLayer(std::uint64_t blocks, std::uint64_t block_bytes, const std::string& name,
                       bool zero);
  /// Zeroes TSDF layer 0 from slot `first_block_0` and every other layer from `first_block`.
  void zeroLayers(std::uint32_t first_block_0, std::uint32_t first_block);
  vk::Buffer& tsdfLayer(int layer);
  const vk::Buffer& tsdfLayer(int layer) const;
  vk::Buffer& labelLayer(int layer);
  const vk::Buffer& labelLayer(int layer) const;

  vk::Context& context_;
  MapConfig config_;
  vk::Buffer entries_;
  vk::Buffer counters_;
  std::vector<vk::Buffer> tsdf_layers_;  // [0]: the map every kernel uses by default
  std::vector<vk::Buffer> label_layers_;
  std::uint32_t block_count_ = 0;
  std::uint32_t block_capacity_ = 0;
  std::uint32_t hash_capacity_ = 0;
};

}  // namespace strata
