#pragma once
// Change detection on the device (docs/change.md, steps 2-5) over the layers of one
// DeviceTsdfMap: differencing, erosion, dilation, static update and the dynamic parts asked for,
// recorded in one submission with a timestamp after each stage. Rules: change_rules.h; C++
// reference: change_reference.h. Every pass runs over all allocated slots; layers share slots, so
// the per-voxel passes stream the pools and only erosion/dilation look at neighbours (through a
// table of the 27 blocks around each block, built first), on bit masks of the dynamic voxels of
// each row of 8 (change_rows.glsl).
// Thread safety: not thread safe.
#include <array>
#include <memory>
#include <utility>
#include <vector>

#include "strata/change/change_config.h"
#include "strata/change/change_labels.h"
#include "strata/map/device_tsdf_map.h"
#include "strata/vk/vk.h"

namespace strata::change {

/// Which layers of the map one session update reads and writes.
struct ChangeLayers {
  int static_tsdf = 0;   // S: read and written
  int session_tsdf = 1;  // M_N: the session being merged
  int labels = 0;        // D: label layer written (kUnknown where S or M_N is unobserved)
  int raw_scratch = 1;   // label layer overwritten in between (raw labels)
  /// (TSDF layer of session i, label layer of its dynamic part) for every session whose dynamic
  /// part is (re)computed against S.
  std::vector<std::pair<int, int>> session_parts;
};

/// Dynamic parts computed by DeviceChange::dynamicParts.
struct DynamicPartStats {
  double device_ms = 0.0;                     // timestamp queries, all parts
  std::vector<std::uint64_t> dynamic_voxels;  // per entry of ChangeLayers::session_parts
};

class DeviceChange {
 public:
  /// `map` must outlive this object.
  DeviceChange(vk::Context& context, DeviceTsdfMap& map, const ChangeConfig& config);
  ~DeviceChange();

  /// One session update: D = clean(difference(S, M_N)) with DilationMask::kObserved;
  /// S = mergeStatic(S, M_N, D); then for every session part i: P_i = clean(sessionDynamic(M_i, S))
  /// with DilationMask::kRawDynamic (the part's counts go to session_dynamic_voxels, summed).
  /// Blocks until done; device ms per stage from timestamps.
  ChangeUpdateStats update(const ChangeLayers& layers);
  /// Only the dynamic parts of layers.session_parts against S (S, D unchanged).
  DynamicPartStats dynamicParts(const ChangeLayers& layers);

  const ChangeConfig& config() const { return config_; }
  /// Layers larger than this are reached by device address instead of a binding (default and
  /// upper bound: the device's maxStorageBufferRange). Tests lower it to cover that path.
  void setBindingLimit(std::uint64_t bytes);

 private:
  /// The kernels, reaching the layers through bindings or by device address (layers larger than
  /// one binding's range; slower on lavapipe).
  struct Pipelines;
  Pipelines& pipelines(bool by_address);
  /// Dispatches every kernel once on no work: lavapipe compiles a kernel at its first dispatch,
  /// which would otherwise be timed as part of the first update.
  void warmUp();
  /// Records the passes (the static update when `merge`) in one submission and waits; the
  /// counters of every pass are left in counts_.
  void run(const ChangeLayers& layers, bool merge);
  void recordMerge(vk::CommandBuffer& cmd, const ChangeLayers& layers, Pipelines& p);
  void recordParts(vk::CommandBuffer& cmd, const ChangeLayers& layers, Pipelines& p);
  void recordNeighbours(vk::CommandBuffer& cmd);
  void recordVoxelPass(vk::CommandBuffer& cmd, const vk::ComputePipeline& pipeline, int s_layer,
                       int m_layer, int label_layer, std::uint32_t counter);
  void recordErosion(vk::CommandBuffer& cmd, Pipelines& p, std::uint32_t counter);
  void recordDilation(vk::CommandBuffer& cmd, Pipelines& p, int raw, int out, std::uint32_t mask,
                      std::uint32_t counter);
  /// Raw labels of one voxel pass into layers.raw_scratch and the raw row mask.
  void recordRawPass(vk::CommandBuffer& cmd, const vk::ComputePipeline& pipeline, int s_layer,
                     int m_layer, int raw_layer, std::uint32_t counter);
  void ensureBuffers(std::uint32_t blocks, std::uint32_t counters);

  vk::Context& context_;
  DeviceTsdfMap& map_;
  ChangeConfig config_;
  vk::ComputePipeline neighbours_;
  std::array<std::unique_ptr<Pipelines>, 2> pipelines_;  // [by_address], made on first use
  vk::Buffer neighbour_slots_;                           // 27 int per slot
  vk::Buffer raw_mask_;  // dynamic row masks (change_rows.glsl), 64 words per slot
  vk::Buffer eroded_mask_;
  vk::Buffer near_dynamic_;  // per slot: an eroded dynamic voxel within one block
  vk::Buffer counters_;      // dynamic labels written by each pass
  vk::Buffer counters_readback_;
  vk::TimestampQueries timer_;
  std::uint64_t binding_limit_bytes_ = ~std::uint64_t{0};
  std::vector<vk::DescriptorSet> sets_;  // of the run being recorded (kept until it completes)
  std::vector<std::uint32_t> counts_;
};

/// Explicit device->host copy of a label layer (every allocated block).
LabelMap downloadLabels(DeviceTsdfMap& map, int label_layer);

}  // namespace strata::change
