#pragma once
// The block-sparse TSDF map on the device: an open-addressing hash table from block key to pool
// slot (kernels insert with 64-bit atomics), and the TSDF voxel pool addressed by device address.
// Both grow on demand; when the device cannot hold more, an error says how many blocks were asked
// for and the map stays as it was.
#include <cstdint>

#include "map/map_config.h"
#include "map/tsdf_map.h"
#include "vk/vk.h"

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
  std::uint64_t poolAddress() const { return pool_.deviceAddress(); }
  std::uint64_t deviceBytes() const { return pool_.size() + entries_.size() + counters_.size(); }
  /// Bytes of device memory per voxel of the pool (voxel payload only).
  static constexpr std::uint32_t kBytesPerVoxel = sizeof(TsdfVoxel);

  vk::Buffer& hashEntries() { return entries_; }
  vk::Buffer& counters() { return counters_; }
  vk::Buffer& pool() { return pool_; }

  /// Record that the device handed out `block_count` slots. Grows the pool (device-side copy) when
  /// they exceed capacity; when the device cannot hold them, removes the blocks that have no slot
  /// from the table and throws DeviceError naming the number of blocks asked for.
  void commitBlockCount(std::uint32_t block_count);
  /// Rebuilds the hash table with at least `min_capacity` entries (power of two), keeping slots.
  void growHash(std::uint32_t min_capacity);
  /// Grow the table when it is more than half full, so probes stay short.
  void maintainLoadFactor();

  /// Explicit device->host copy of the whole map.
  void download(TsdfMap& out);
  /// Replaces the device map with `map` (same config required).
  void upload(const TsdfMap& map);

 private:
  std::vector<std::pair<std::uint64_t, std::uint32_t>> readTable();
  void writeTable(const std::vector<std::pair<std::uint64_t, std::uint32_t>>& key_slots,
                  std::uint32_t capacity);
  void growPool(std::uint32_t min_blocks);
  void writeCounters();

  vk::Context& context_;
  MapConfig config_;
  vk::Buffer entries_;
  vk::Buffer counters_;
  vk::Buffer pool_;
  std::uint32_t block_count_ = 0;
  std::uint32_t block_capacity_ = 0;
  std::uint32_t hash_capacity_ = 0;
};

}  // namespace strata
