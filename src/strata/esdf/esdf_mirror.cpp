// DeviceEsdf's host mirror of slot -> block (read back from the hash table by esdf_slot_keys.comp)
// and the growth of the slot-aligned ESDF pool.
#include <algorithm>

#include "strata/core/error.h"
#include "strata/map/device_layout.h"
#include "strata/esdf/internal/esdf_impl.h"
#include "strata/vk/dispatch_size.h"

namespace strata {
namespace {

using vk::kMaxGroupsPerDimension;

void ensureSlotKeys(vk::Context& context, std::uint32_t blocks, EsdfDeviceState& impl) {
  if (blocks <= impl.slot_keys_capacity) return;
  impl.slot_keys_capacity = std::max(blocks, impl.slot_keys_capacity * 2);
  impl.slot_keys = vk::Buffer::create(context, std::uint64_t{impl.slot_keys_capacity} * 8,
                                      vk::MemoryUsage::kDeviceLocal, "ESDF slot keys");
}

/// Runs esdf_slot_keys.comp over the whole hash table.
void writeSlotKeys(vk::Context& context, DeviceTsdfMap& tsdf, EsdfDeviceState& impl) {
  const gpu::EsdfSlotKeysPush push{tsdf.hashCapacity(), impl.slot_keys_capacity};
  vk::DescriptorSet set = vk::DescriptorSet::create(context, impl.slot_keys_pipeline,
                                                    {&tsdf.hashEntries(), &impl.slot_keys});
  const std::uint32_t groups = (push.entry_count + 255) / 256;
  const std::uint32_t groups_x = std::min(groups, kMaxGroupsPerDimension);
  vk::CommandBuffer cmd = vk::CommandBuffer::create(context);
  cmd.begin();
  cmd.fill(impl.slot_keys, 0xFFFFFFFFu);  // kEmptyBlockKey for slots without an entry
  cmd.barrier();
  cmd.bind(impl.slot_keys_pipeline, set);
  cmd.pushConstants(impl.slot_keys_pipeline, &push, sizeof(push));
  cmd.dispatch(groups_x, (groups + groups_x - 1) / groups_x);
  cmd.barrier();
  cmd.end();
  cmd.submitAndWait();
}

}  // namespace

std::uint32_t syncSlotBlocks(vk::Context& context, DeviceTsdfMap& tsdf, EsdfDeviceState& impl,
                             bool full) {
  const std::uint32_t count = tsdf.blockCount();
  // Fewer blocks than mirrored: the map was replaced (DeviceTsdfMap::upload); start over.
  if (count < impl.slot_blocks.size()) full = true;
  if (full) {
    impl.slot_blocks.clear();
    impl.map_box = BlockBox{};
  }
  const auto first_new = static_cast<std::uint32_t>(impl.slot_blocks.size());
  if (count == first_new) return first_new;
  ensureSlotKeys(context, count, impl);
  writeSlotKeys(context, tsdf, impl);
  std::vector<std::uint64_t> keys(count - first_new);
  vk::download(context, impl.slot_keys, keys.data(), keys.size() * 8, std::size_t{first_new} * 8);
  for (const std::uint64_t key : keys) {
    // Every slot below the block count has an entry; an empty key would be a broken map.
    if (key == kEmptyBlockKey) {
      throw DeviceError("ESDF: a TSDF pool slot below the block count has no hash-table entry");
    }
    impl.slot_blocks.push_back(unpackBlockKey(key));
    impl.map_box.include(impl.slot_blocks.back());
  }
  return first_new;
}

void ensureEsdfPool(vk::Context& context, const DeviceTsdfMap& tsdf, EsdfDeviceState& impl) {
  const std::uint32_t needed = std::max(tsdf.blockCount(), 1u);
  if (needed <= impl.pool_blocks) return;
  const std::uint32_t blocks = std::max(needed, tsdf.blockCapacity());
  vk::Buffer pool = vk::Buffer::create(context, blocks * kEsdfBlockBytes,
                                       vk::MemoryUsage::kDeviceLocal, "ESDF voxel pool");
  const std::uint64_t kept_bytes = std::uint64_t{impl.computed_blocks} * kEsdfBlockBytes;
  vk::CommandBuffer cmd = vk::CommandBuffer::create(context);
  cmd.begin();
  if (kept_bytes > 0) cmd.copy(impl.pool, pool, kept_bytes);
  cmd.fill(pool, 0u, kept_bytes, pool.size() - kept_bytes);  // unobserved, no site
  cmd.barrier();
  cmd.end();
  cmd.submitAndWait();
  impl.pool = std::move(pool);
  impl.pool_blocks = blocks;
}

}  // namespace strata
