#pragma once
// Fusion of RGB-D frames into the device map in one submission per frame: upload, depth normals
// and quarter-tile depth ranges (estimate_normals.comp), block allocation (allocate_blocks.comp),
// the integration group counts (integrate_args.comp) and TSDF integration through an indirect
// dispatch (integrate_tsdf.comp). The pool is grown ahead of the frame so nothing is read back in
// the middle; when a pass overflows anyway (hash probes, touched list, pool), nothing is
// integrated, the host grows what filled and runs allocation and integration again; when it cannot
// grow, the frame is refused whole (its blocks forgotten). Blocks until the frame is fused.
// Thread safety: not thread safe; one DeviceFusion per thread.
#include <cstdint>
#include <vector>

#include "strata/core/types.h"
#include "strata/map/camera_math.h"
#include "strata/map/device_layout.h"
#include "strata/map/device_tsdf_map.h"
#include "strata/vk/vk.h"

namespace strata {

/// Timings of one frame. Device times come from timestamp queries.
struct FrameStats {
  double upload_ms = 0.0;     // host->device copy of depth and colour (device time)
  double normals_ms = 0.0;    // depth normals and quarter-tile depth ranges (device time)
  double allocate_ms = 0.0;   // block allocation and integration arguments (device, all passes)
  double integrate_ms = 0.0;  // TSDF integration (device time)
  double wall_ms = 0.0;       // host wall time of the whole call
  std::uint32_t touched_blocks = 0;
  std::uint32_t allocation_passes = 0;  // > 1 when the table, touched list or pool had to grow
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
  /// A descriptor set kept across frames while its buffers stay the same (by Buffer::id).
  struct CachedSet {
    std::vector<std::uint64_t> ids;
    vk::DescriptorSet set;
  };
  const vk::DescriptorSet& cachedSet(CachedSet& cache, const vk::ComputePipeline& pipeline,
                                     const std::vector<const vk::Buffer*>& buffers);

  void stageFrame(const RgbdFrame& frame);
  void ensureFrameBuffers(std::size_t pixel_count, std::uint32_t tile_count);
  void reserveAhead();
  /// Runs passes until one fits, growing what filled; DeviceError (the frame's blocks forgotten)
  /// when the map cannot grow.
  gpu::MapCounters runPasses(const FrameCamera& camera, bool has_color, int layer,
                             FrameStats& stats);
  /// Records and submits one pass (upload and normals on the first), reads the counters back.
  gpu::MapCounters runPass(const FrameCamera& camera, bool first_pass, bool has_color, int layer,
                           FrameStats& stats);
  void recordNormals(vk::CommandBuffer& cmd, const FrameCamera& camera);
  void recordAllocation(vk::CommandBuffer& cmd, const FrameCamera& camera);
  void recordIntegration(vk::CommandBuffer& cmd, const FrameCamera& camera, bool has_color,
                         int layer);
  void recordTouchedGather(vk::CommandBuffer& cmd);
  void readTouchedBlocks(std::uint32_t touched);
  /// Grows what the counters say filled; true when the pass must run again.
  bool growAfterOverflow(const gpu::MapCounters& counters);

  vk::Context& context_;
  DeviceTsdfMap map_;
  vk::ComputePipeline allocate_pipeline_;
  vk::ComputePipeline integrate_pipeline_;
  vk::ComputePipeline normals_pipeline_;
  vk::ComputePipeline args_pipeline_;
  vk::CommandBuffer commands_;
  vk::Buffer depth_staging_;
  vk::Buffer color_staging_;
  vk::Buffer depth_;
  vk::Buffer color_;
  vk::Buffer normals_;
  vk::Buffer quarter_ranges_;
  vk::Buffer touched_;
  vk::Buffer dispatch_args_;
  vk::Buffer counters_readback_;
  vk::TimestampQueries timer_;
  CachedSet normals_set_;
  CachedSet allocate_set_;
  CachedSet args_set_;
  CachedSet integrate_set_;
  CachedSet gather_set_;
  std::size_t pixel_capacity_ = 0;
  std::uint32_t tile_capacity_ = 0;
  std::uint32_t tile_count_ = 0;
  std::uint32_t touched_capacity_ = 0;
  std::uint32_t last_touched_count_ = 0;
  std::uint32_t pass_id_ = 0;
  // Touched-block tracking (setTrackTouchedBlocks).
  bool track_touched_ = false;
  vk::ComputePipeline touched_keys_pipeline_;
  vk::Buffer touched_keys_;
  std::vector<BlockIndex> last_touched_;
};

}  // namespace strata
