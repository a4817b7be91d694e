#pragma once
// Kernel 3, raycast: render the map into a pinhole camera. Device: shaders/raycast_tsdf.comp via
// RaycastKernel; the reference (raycastReference) marches the same way on the host map.
#include <cstdint>
#include <vector>

#include "strata/core/types.h"
#include "strata/map/camera_math.h"
#include "strata/map/tsdf_map.h"
#include "strata/vk/vk.h"

namespace strata {

class DeviceTsdfMap;

struct RaycastOptions {
  /// Voxels with less weight count as unobserved (rays pass through them).
  float min_weight = 1e-6f;
  /// Upper bound on march steps per ray (the march stops earlier at max depth).
  std::uint32_t max_steps = 4096;
  /// TSDF layer of the device map that is marched (device kernels only; 0: the default layer).
  int tsdf_layer = 0;
};

struct RaycastImage {
  DepthImage depth;                      // z in the camera frame, 0 where the ray missed
  std::vector<Eigen::Vector3f> normal_W; // unit normal (world), zero where missed/unknown
  ColorImage color;                      // voxel colour at the hit
  std::vector<std::uint8_t> hit;         // 1 where the ray hit a surface
};

/// Host reference of raycast_tsdf.comp.
RaycastImage raycastReference(const TsdfMap& map, const CameraIntrinsics& intrinsics,
                              const Eigen::Isometry3d& T_W_C, const RaycastOptions& options = {});

/// One ray of raycastReference (the same march): true on a hit, with the distance along the unit
/// direction dir_W in *t_hit. Used by the sparse raycast of keyframe selection (select_samples.h).
bool raycastRayReference(const TsdfMap& map, const Eigen::Vector3f& origin_W,
                         const Eigen::Vector3f& dir_W, float t_min, float t_max,
                         const RaycastOptions& options, float* t_hit);

/// Device raycast with its output buffers kept between calls.
class RaycastKernel {
 public:
  explicit RaycastKernel(vk::Context& context);
  /// Renders `map` from T_W_C; returns the images and the device time in *device_ms if non-null.
  RaycastImage run(DeviceTsdfMap& map, const CameraIntrinsics& intrinsics,
                   const Eigen::Isometry3d& T_W_C, const RaycastOptions& options = {},
                   double* device_ms = nullptr);
  /// The same march, outputs left on the device (depthBuffer(), normalBuffer(): float z and
  /// vec4 world normal with w = 1 on a hit, row-major); returns the device time in ms.
  double render(DeviceTsdfMap& map, const CameraIntrinsics& intrinsics,
                const Eigen::Isometry3d& T_W_C, const RaycastOptions& options = {});
  const vk::Buffer& depthBuffer() const { return depth_out_; }
  const vk::Buffer& normalBuffer() const { return normal_out_; }

 private:
  void ensureOutputs(std::size_t pixel_count);
  vk::Context& context_;
  vk::ComputePipeline pipeline_;
  vk::Buffer depth_out_;
  vk::Buffer normal_out_;
  vk::Buffer color_out_;
  vk::TimestampQueries timer_;
  std::size_t pixel_capacity_ = 0;
};

}  // namespace strata
