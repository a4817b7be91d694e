#pragma once
// DeviceEsdf's state and the steps of an update (internal): the host mirror of slot -> block, the
// ESDF pool, and the recording of the dense passes (esdf_dispatch.cpp).
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "strata/esdf/esdf.h"
#include "strata/esdf/esdf_plan.h"
#include "strata/esdf/esdf_rules.h"

namespace strata {

/// The kernels of the dense passes, specialised for reaching the working box and the pools through
/// bindings (faster) or by device address (buffers beyond one binding's range); esdf_access.glsl.
struct EsdfPipelines {
  EsdfPipelines(vk::Context& context, bool box_by_address, bool pools_by_address);
  vk::ComputePipeline gather;
  vk::ComputePipeline edt;
  vk::ComputePipeline scatter;
};

/// Everything DeviceEsdf keeps between updates (DeviceEsdf::Impl is this; a plain struct so the
/// step functions below can take it).
struct EsdfDeviceState {
  explicit EsdfDeviceState(vk::Context& context);

  vk::ComputePipeline slot_keys_pipeline;
  /// Indexed by box_by_address + 2 * pools_by_address; made on first use.
  std::array<std::unique_ptr<EsdfPipelines>, 4> pipelines;
  vk::TimestampQueries timer;

  /// ESDF voxels, slot-aligned with the TSDF pool (4096 bytes per slot).
  vk::Buffer pool;
  std::uint32_t pool_blocks = 0;
  /// slot -> packed block key, written by esdf_slot_keys.comp.
  vk::Buffer slot_keys;
  std::uint32_t slot_keys_capacity = 0;

  /// Host mirror: block of each slot, and the box of all of them.
  std::vector<BlockIndex> slot_blocks;
  BlockBox map_box;
  /// Blocks whose ESDF holds a computed value (slots below this count).
  std::uint32_t computed_blocks = 0;
  /// Blocks marked dirty since the last update.
  std::vector<BlockIndex> dirty;

  /// Working memory of the dense passes, reused between updates (grow only).
  vk::Buffer box;
  vk::Buffer scratch;
  vk::Buffer lists;  // ListedBlock gather/scatter lists of all jobs (host upload)
  std::uint64_t max_box_bytes = 512ull << 20;
  std::uint64_t max_scratch_bytes = 64ull << 20;
  /// Buffers above this are reached by device address (esdf_access.glsl).
  std::uint64_t binding_limit_bytes = ~0ull;
};

struct DeviceEsdf::Impl : EsdfDeviceState {
  using EsdfDeviceState::EsdfDeviceState;
};

/// Brings the slot -> block mirror up to date with the device map (all slots when `full`, else
/// only slots handed out since the last sync). Returns the first slot that is new.
std::uint32_t syncSlotBlocks(vk::Context& context, DeviceTsdfMap& tsdf, EsdfDeviceState& impl,
                             bool full);
/// Grows the ESDF pool to the TSDF pool's capacity, keeping computed blocks; new slots start zero.
void ensureEsdfPool(vk::Context& context, const DeviceTsdfMap& tsdf, EsdfDeviceState& impl);
/// Records and runs every job in one submission; returns the device time (timestamp queries).
double runEsdfJobs(vk::Context& context, DeviceTsdfMap& tsdf, const EsdfConfig& config,
                   const std::vector<EsdfJob>& jobs, EsdfDeviceState& impl);

}  // namespace strata
