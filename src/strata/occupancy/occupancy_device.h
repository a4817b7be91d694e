#pragma once
// The OctoMap-style occupancy layer on the device, sharing the block index of a DeviceTsdfMap.
// Per depth frame (one scan), three kernels:
//   occupancy_allocate.comp  every block holding a voxel a ray updates is allocated (the
//                            fusion's free-space allocation is a sparse pixel grid and misses
//                            blocks; a voxel needs its block to hold marks): a walk over blocks,
//                            and the exact walk over voxels when the mark pass finds a gap;
//   occupancy_mark.comp      rays mark misses / hits in a state layer with atomics;
//   occupancy_update.comp    one log-odds update per marked voxel, hit over miss (OctoMap's
//                            per-scan rule), Eq. (2)-(3) of Hornung et al. 2013.
// Reference: integrateOccupancyReference (occupancy_reference.h), equal voxel for voxel.
// Two label layers of the map hold the layer: state bits (occupancy_rules.h) and the log-odds as
// float bits; blocks allocated here exist (unobserved) in the TSDF layers too. DeviceTsdfMap::
// upload() resets every label layer, so the occupancy too (uploadLayer() keeps it).
// Thread safety: not thread safe; use from the thread that uses the map.
#include <cstdint>

#include "strata/core/types.h"
#include "strata/map/camera_math.h"
#include "strata/map/device_layout.h"
#include "strata/map/device_tsdf_map.h"
#include "strata/occupancy/occupancy_layout.h"
#include "strata/occupancy/occupancy_map.h"
#include "strata/occupancy/occupancy_reference.h"
#include "strata/vk/vk.h"

namespace strata {

/// Timings of one frame; device times from timestamp queries.
struct OccupancyFrameStats {
  double upload_ms = 0.0;               // depth host->device copy
  double allocate_ms = 0.0;             // block allocation, summed over passes
  double mark_ms = 0.0;                 // rays marking misses and hits
  double update_ms = 0.0;               // one update per marked voxel
  double wall_ms = 0.0;                 // host wall time of the whole call
  std::uint32_t touched_blocks = 0;     // blocks with a marked voxel
  std::uint32_t allocation_passes = 0;  // > 1 when the hash table had to grow
  std::uint32_t exact_fallbacks = 0;    // 1 when the block walk missed a block (voxel walk ran)
  double deviceMs() const { return upload_ms + allocate_ms + mark_ms + update_ms; }
};

class DeviceOccupancy {
 public:
  /// Validates `config` (InputError) and adds the two label layers to `map`, which must outlive
  /// this object. Layers start unknown everywhere.
  DeviceOccupancy(DeviceTsdfMap& map, const OccupancyConfig& config);

  /// One scan from the frame's depth and pose (colour ignored). Bad input throws InputError before
  /// the device changes; a full device throws DeviceError (blocks allocated before stay).
  OccupancyFrameStats integrate(const RgbdFrame& frame, const CameraIntrinsics& intrinsics);

  /// Explicit device->host copy of the layer: every block with an observed voxel.
  void download(OccupancyMap& out);

  /// Always allocate with the exact voxel walk (slower; the result is the same): for tests.
  void setExactAllocation(bool on) { exact_allocation_ = on; }

  const OccupancyConfig& config() const { return config_; }
  DeviceTsdfMap& map() { return map_; }
  int stateLayer() const { return state_layer_; }
  int logOddsLayer() const { return log_odds_layer_; }

 private:
  void stageDepth(const DepthImage& depth);
  gpu::OccupancyRayPush rayPush(const FrameCamera& camera) const;
  void allocate(const FrameCamera& camera, bool walk_blocks, bool& upload,
                OccupancyFrameStats& stats);
  gpu::MapCounters runAllocation(const gpu::OccupancyRayPush& push, bool upload,
                                 OccupancyFrameStats& stats);
  void ensureSlotBuffers();
  gpu::OccupancyCounters mark(const FrameCamera& camera, OccupancyFrameStats& stats);
  gpu::OccupancyCounters runMark(const gpu::OccupancyRayPush& push, OccupancyFrameStats& stats);
  void runUpdate(std::uint32_t touched, OccupancyFrameStats& stats);
  void rayGroups(std::uint32_t& x, std::uint32_t& y) const;

  DeviceTsdfMap& map_;
  OccupancyConfig config_;
  int state_layer_ = -1;
  int log_odds_layer_ = -1;
  vk::ComputePipeline allocate_pipeline_;
  vk::ComputePipeline mark_pipeline_;
  vk::ComputePipeline mark_by_address_pipeline_;  // made when the state layer outgrows a binding
  vk::ComputePipeline update_pipeline_;
  vk::Buffer depth_staging_;
  vk::Buffer depth_;
  vk::Buffer block_stamps_;   // uint per slot: frame id of the last listing
  vk::Buffer touched_slots_;  // slots with a mark this frame
  vk::Buffer counters_;       // gpu::OccupancyCounters
  vk::Buffer readback_;       // counters of either pass
  vk::TimestampQueries timer_;
  std::uint64_t pixel_capacity_ = 0;
  std::uint32_t slot_capacity_ = 0;
  std::uint32_t frame_id_ = 0;
  int width_px_ = 0;
  int height_px_ = 0;
  bool exact_allocation_ = false;
};

}  // namespace strata
