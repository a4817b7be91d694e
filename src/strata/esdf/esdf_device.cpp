// DeviceEsdf: the public steps (mark dirty, update all / incrementally, download). An update
// computes the exact ESDF of a box of blocks in a dense working box on the device (see
// esdf_edt_pass.comp for the algorithm and why); the incremental box is every block a dirty block
// can influence (its AABB dilated by the max distance), with sites from that box dilated again.
#include <chrono>

#include "strata/core/clock.h"
#include "strata/map/device_layout.h"
#include "strata/esdf/internal/esdf_impl.h"

namespace strata {
namespace {

using Clock = std::chrono::steady_clock;

/// Blocks covered by the max distance, rounded up: a voxel within reach of a block lies in it or
/// in a block at most this many blocks away along each axis.
int reachBlocks(const EsdfConfig& config, float voxel_size_m) {
  const int voxels = esdfReach(config, voxel_size_m).max_voxels;
  return (voxels + kBlockEdge - 1) / kBlockEdge;
}

/// Recomputes every allocated block inside `box` (dilated/clipped by planEsdfJobs).
EsdfUpdateStats runUpdate(vk::Context& context, DeviceTsdfMap& tsdf, const EsdfConfig& config,
                          const BlockBox& box, bool full, EsdfDeviceState& impl) {
  const auto wall_start = Clock::now();
  EsdfUpdateStats stats;
  stats.full = full;
  ensureEsdfPool(context, tsdf, impl);
  const std::vector<EsdfJob> jobs =
      planEsdfJobs(box, impl.map_box, reachBlocks(config, tsdf.config().voxel_size_m),
                   impl.slot_blocks, impl.max_box_bytes / 4);
  stats.device_ms = runEsdfJobs(context, tsdf, config, jobs, impl);
  stats.slabs = static_cast<std::uint32_t>(jobs.size());
  for (const EsdfJob& job : jobs) {
    stats.blocks_updated += static_cast<std::uint32_t>(job.scatter.size());
  }
  stats.voxels_updated = std::uint64_t{stats.blocks_updated} * kVoxelsPerBlock;
  impl.computed_blocks = static_cast<std::uint32_t>(impl.slot_blocks.size());
  impl.dirty.clear();
  stats.wall_ms = msSince(wall_start);
  return stats;
}

}  // namespace

EsdfPipelines::EsdfPipelines(vk::Context& context, bool box_by_address, bool pools_by_address)
    : gather(vk::ComputePipeline::create(context, "esdf_gather_sites", 3,
                                         sizeof(gpu::EsdfBlockPush),
                                         {box_by_address, pools_by_address})),
      edt(vk::ComputePipeline::create(context, "esdf_edt_pass", 2, sizeof(gpu::EsdfEdtPush),
                                      {box_by_address, pools_by_address})),
      scatter(vk::ComputePipeline::create(context, "esdf_scatter", 4, sizeof(gpu::EsdfBlockPush),
                                          {box_by_address, pools_by_address})) {}

EsdfDeviceState::EsdfDeviceState(vk::Context& context)
    : slot_keys_pipeline(
          vk::ComputePipeline::create(context, "esdf_slot_keys", 2, sizeof(gpu::EsdfSlotKeysPush))),
      pipelines{std::make_unique<EsdfPipelines>(context, false, false)},
      timer(vk::TimestampQueries::create(context, 2)) {}

DeviceEsdf::DeviceEsdf(vk::Context& context, DeviceTsdfMap& tsdf, const EsdfConfig& config)
    : context_(context), tsdf_(tsdf), config_(config) {
  config_.validate(tsdf.config().voxel_size_m);
  impl_ = std::make_unique<Impl>(context);
}

DeviceEsdf::~DeviceEsdf() = default;

void DeviceEsdf::markDirty(const std::vector<BlockIndex>& blocks) {
  impl_->dirty.insert(impl_->dirty.end(), blocks.begin(), blocks.end());
}

void DeviceEsdf::setWorkingMemoryBudget(std::uint64_t box_bytes, std::uint64_t scratch_bytes) {
  impl_->max_box_bytes = box_bytes;
  impl_->max_scratch_bytes = scratch_bytes;
}

EsdfUpdateStats DeviceEsdf::updateAll() {
  syncSlotBlocks(context_, tsdf_, *impl_, true);
  return runUpdate(context_, tsdf_, config_, impl_->map_box, true, *impl_);
}

EsdfUpdateStats DeviceEsdf::updateIncremental() {
  const std::uint32_t first_new = syncSlotBlocks(context_, tsdf_, *impl_, false);
  // Blocks allocated since the last update hold no ESDF yet: recompute them too.
  const std::uint32_t first_uncomputed = std::min(first_new, impl_->computed_blocks);
  BlockBox dirty_box;
  for (const BlockIndex& b : impl_->dirty) dirty_box.include(b);
  for (std::size_t s = first_uncomputed; s < impl_->slot_blocks.size(); ++s) {
    dirty_box.include(impl_->slot_blocks[s]);
  }
  const int reach = reachBlocks(config_, tsdf_.config().voxel_size_m);
  return runUpdate(context_, tsdf_, config_, dirty_box.dilated(reach), false, *impl_);
}

void DeviceEsdf::download(EsdfMap& out) {
  out = EsdfMap{};
  out.voxel_size_m = tsdf_.config().voxel_size_m;
  out.config = config_;
  const std::uint32_t count = impl_->computed_blocks;
  if (count == 0) return;
  std::vector<EsdfBlock> blocks(count);
  vk::download(context_, impl_->pool, blocks.data(), blocks.size() * sizeof(EsdfBlock));
  for (std::uint32_t s = 0; s < count; ++s) out.blocks.emplace(impl_->slot_blocks[s], blocks[s]);
}

void DeviceEsdf::setBindingLimit(std::uint64_t bytes) { impl_->binding_limit_bytes = bytes; }

const vk::Buffer& DeviceEsdf::pool() const { return impl_->pool; }

std::uint32_t DeviceEsdf::computedBlockCount() const { return impl_->computed_blocks; }

}  // namespace strata
