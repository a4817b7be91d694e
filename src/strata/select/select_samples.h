#pragma once
// Sparse raycast for keyframe selection: the map rendered into a camera on a pixel grid
// (every stride-th pixel, centred). Device: shaders/raycast_samples.comp via SampleRaycastKernel;
// the reference (raycastSamplesReference) marches each sample's ray like raycastReference.
#include <cstdint>
#include <vector>

#include "strata/core/types.h"
#include "strata/raycast/raycast.h"
#include "strata/map/tsdf_map.h"
#include "strata/vk/vk.h"

namespace strata {

class DeviceTsdfMap;

/// The sample grid of an image: sample (gx, gy) looks through pixel (offset + gx * stride,
/// offset + gy * stride) with offset = stride / 2.
struct SampleGrid {
  int stride_px = 10;
  int width = 0;   // samples per row
  int height = 0;  // rows
  int offset_px = 5;

  /// Throws InputError for a stride < 1 or larger than the image.
  static SampleGrid of(const CameraIntrinsics& intrinsics, int stride_px);
  int count() const { return width * height; }
  int pixelU(int gx) const { return offset_px + gx * stride_px; }
  int pixelV(int gy) const { return offset_px + gy * stride_px; }
};

/// Does the map hold the surface the keyframe measured at a sample?
enum class SurfaceCheck : std::uint8_t {
  kNoMeasurement = 0,  // no measured depth there (or no keyframe given)
  kHeld = 1,           // the map's interpolated distance at the measured point is within tolerance
  kNotHeld = 2,        // unobserved there, or the map's surface lies farther away
};

/// The keyframe's measured depth at each sample (camera z, 0 = none), for the surface check.
struct MeasuredSamples {
  std::vector<float> depth_m;
  /// The map holds a measured point when |interpolated TSDF| there is at most this.
  float held_tolerance_m = 0.1f;

  /// InputError unless there is one depth per sample and the tolerance is >= 0.
  void validate(std::size_t sample_count) const;
};

/// What each sample's ray found, row-major over the grid.
struct SampleRaycast {
  SampleGrid grid;
  std::vector<std::uint8_t> hit;          // 1 where the ray hit a surface
  std::vector<float> depth_m;             // camera z of the hit, 0 on a miss
  std::vector<std::uint32_t> color_rgba;  // r | g << 8 | b << 16 of the voxel at the hit, 0 if none
  std::vector<SurfaceCheck> surface;      // kNoMeasurement everywhere without MeasuredSamples
};

/// Host reference of raycast_samples.comp. With `measured`, also the surface check at the point
/// each sample's measured depth puts on its ray (the same ray the raycast marches).
SampleRaycast raycastSamplesReference(const TsdfMap& map, const CameraIntrinsics& intrinsics,
                                      const Eigen::Isometry3d& T_W_C, int stride_px,
                                      const RaycastOptions& options = {},
                                      const MeasuredSamples* measured = nullptr);

/// Device sparse raycast with its output buffer kept between calls. Not thread safe.
class SampleRaycastKernel {
 public:
  explicit SampleRaycastKernel(vk::Context& context);
  /// Renders TSDF layer 0 of `map` from T_W_C on the grid; the raycast's device time goes to
  /// *device_ms when non-null. Bad intrinsics/pose/stride throw InputError.
  /// With `measured` (one depth per sample), also the surface check.
  SampleRaycast run(DeviceTsdfMap& map, const CameraIntrinsics& intrinsics,
                    const Eigen::Isometry3d& T_W_C, int stride_px,
                    const RaycastOptions& options = {}, double* device_ms = nullptr,
                    const MeasuredSamples* measured = nullptr);
  /// The last run's samples on the device (uvec2 per sample), for sample_differences.comp.
  const vk::Buffer& samplesBuffer() const { return samples_out_; }

 private:
  void ensureOutput(std::size_t sample_count);
  void uploadMeasured(const MeasuredSamples* measured, std::size_t sample_count);
  vk::Context& context_;
  vk::ComputePipeline pipeline_;
  vk::Buffer samples_out_;
  vk::Buffer measured_;  // held tolerance, then one depth per sample
  vk::TimestampQueries timer_;
  std::size_t sample_capacity_ = 0;
};

}  // namespace strata
