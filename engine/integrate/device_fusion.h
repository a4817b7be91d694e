#pragma once
// Fusion of RGB-D frames into the device map: upload, block allocation (allocate_blocks.comp),
// TSDF integration (integrate_tsdf.comp). One frame at a time; blocks until the frame is fused.
// Thread safety: not thread safe; one DeviceFusion per thread.
#include <cstdint>
#include <vector>

#include "core/types.h"
#include "map/camera_math.h"
#include "map/device_layout.h"
#include "map/device_tsdf_map.h"
#include "vk/vk.h"

namespace strata {

/// Timings of one frame. Device times come from timestamp queries.
struct FrameStats {
  double upload_ms = 0.0;     // host->device copy of depth and colour (device time)
  double normals_ms = 0.0;    // depth normals for the point-to-plane distance (device time)
  double allocate_ms = 0.0;   // block allocation (device time, summed over passes)
  double integrate_ms = 0.0;  // TSDF integration (device time)
  double wall_ms = 0.0;       // host wall time of the whole call
  std::uint32_t touched_blocks = 0;
  std::uint32_t allocation_passes = 0;  // > 1 when the table or touched list had to grow
};

class DeviceFusion {
 public:
  DeviceFusion(vk::Context& context, const MapConfig& config);

  /// Fuses one frame into TSDF layer `layer` of the map (blocks are allocated for all layers).
  /// Bad input (sizes, pose, intrinsics, a layer the map lacks) throws InputError before anything
  /// on the device changes; a full device throws DeviceError and leaves the map as it was before
  /// the frame.
  FrameStats integrate(const RgbdFrame& frame, const CameraIntrinsics& intrinsics, int layer = 0);

  /// When on, integrate() also lists the blocks it touched (a tiny gather kernel and a readback of
  /// 8 bytes per block), for layers updated incrementally (DeviceEsdf::markDirty). Off by default.
  void setTrackTouchedBlocks(bool on);
  /// Blocks touched by the last integrate() while tracking was on (empty otherwise).
  const std::vector<BlockIndex>& lastTouchedBlocks() const { return last_touched_; }

  DeviceTsdfMap& map() { return map_; }
  const MapConfig& config() const { return map_.config(); }

 private:
  void stageFrame(const RgbdFrame& frame);
  void ensureFrameBuffers(std::size_t pixel_count);
  gpu::MapCounters runAllocation(const FrameCamera& camera, bool upload_frame, FrameStats& stats);
  void runIntegration(const FrameCamera& camera, bool has_color, std::uint32_t touched, int layer,
                      FrameStats& stats);
  void recordTouchedGather(vk::CommandBuffer& cmd, std::uint32_t touched);
  void readTouchedBlocks(std::uint32_t touched);

  vk::Context& context_;
  DeviceTsdfMap map_;
  vk::ComputePipeline allocate_pipeline_;
  vk::ComputePipeline integrate_pipeline_;
  vk::ComputePipeline normals_pipeline_;
  vk::Buffer depth_staging_;
  vk::Buffer color_staging_;
  vk::Buffer depth_;
  vk::Buffer color_;
  vk::Buffer normals_;
  vk::Buffer touched_;
  vk::Buffer counters_readback_;
  vk::TimestampQueries timer_;
  std::size_t pixel_capacity_ = 0;
  std::uint32_t touched_capacity_ = 0;
  std::uint32_t pass_id_ = 0;
  // Touched-block tracking (setTrackTouchedBlocks).
  bool track_touched_ = false;
  vk::ComputePipeline touched_keys_pipeline_;
  vk::Buffer touched_keys_;
  vk::DescriptorSet touched_keys_set_;
  std::vector<BlockIndex> last_touched_;
};

}  // namespace strata
