// Device dispatch of shaders/raycast_samples.comp.
#include "strata/select/select_samples.h"

#include <cmath>
#include <cstring>

#include "strata/map/device_layout.h"
#include "strata/map/device_tsdf_map.h"
#include "strata/select/internal/select_layout.h"
#include "strata/vk/timed_dispatch.h"

namespace strata {

SampleRaycastKernel::SampleRaycastKernel(vk::Context& context)
    : context_(context),
      pipeline_(vk::ComputePipeline::create(context, "raycast_samples", 3,
                                            sizeof(gpu::SampleRaycastPush))),
      timer_(vk::TimestampQueries::create(context, 2)) {}

void SampleRaycastKernel::ensureOutput(std::size_t sample_count) {
  if (sample_count <= sample_capacity_) return;
  samples_out_ = vk::Buffer::create(context_, sample_count * 8, vk::MemoryUsage::kHostReadback,
                                    "raycast samples");
  measured_ = vk::Buffer::create(context_, (sample_count + 1) * 4, vk::MemoryUsage::kHostUpload,
                                 "measured depth at samples");
  sample_capacity_ = sample_count;
}

void SampleRaycastKernel::uploadMeasured(const MeasuredSamples* measured,
                                         std::size_t sample_count) {
  if (measured != nullptr) measured->validate(sample_count);
  // Explicit host->device copy: the tolerance, then the depths (zeros: no surface check).
  auto* floats = static_cast<float*>(measured_.mapped());
  floats[0] = measured != nullptr ? measured->held_tolerance_m : 0.0f;
  for (std::size_t i = 0; i < sample_count; ++i) {
    const float d = measured != nullptr ? measured->depth_m[i] : 0.0f;
    floats[i + 1] = std::isfinite(d) && d > 0.0f ? d : 0.0f;
  }
}

SampleRaycast SampleRaycastKernel::run(DeviceTsdfMap& map, const CameraIntrinsics& intrinsics,
                                       const Eigen::Isometry3d& T_W_C, int stride_px,
                                       const RaycastOptions& options, double* device_ms,
                                       const MeasuredSamples* measured) {
  validatePose(T_W_C, "sample raycast camera");
  SampleRaycast out;
  out.grid = SampleGrid::of(intrinsics, stride_px);
  const std::size_t n = static_cast<std::size_t>(out.grid.count());
  ensureOutput(n);
  uploadMeasured(measured, n);

  const MapConfig& config = map.config();
  const FrameCamera camera = FrameCamera::from(intrinsics, T_W_C);
  gpu::SampleRaycastPush push{};
  gpu::storeMatrix(camera.T_W_C, push.T_W_C);
  for (int i = 0; i < 4; ++i) push.K[i] = camera.K[i];
  push.grid_size[0] = static_cast<std::uint32_t>(out.grid.width);
  push.grid_size[1] = static_cast<std::uint32_t>(out.grid.height);
  push.min_depth_m = config.min_depth_m;
  push.max_depth_m = config.max_depth_m;
  push.voxel_size_m = config.voxel_size_m;
  push.truncation_m = config.truncationDistance();
  push.hash_mask = map.hashMask();
  push.min_weight = options.min_weight;
  push.pool_address = map.poolAddress(options.tsdf_layer);
  push.max_steps = options.max_steps;
  push.stride_px = static_cast<std::uint32_t>(stride_px);

  vk::DescriptorSet set = vk::DescriptorSet::create(
      context_, pipeline_, {&map.hashEntries(), &samples_out_, &measured_});
  const double ms =
      dispatchTimed(context_, pipeline_, set, &push, sizeof(push), (push.grid_size[0] + 15) / 16,
                    (push.grid_size[1] + 15) / 16, timer_);
  if (device_ms != nullptr) *device_ms = ms;

  // Explicit device->host copy of the samples (host-visible readback buffer).
  out.hit.assign(n, 0);
  out.depth_m.assign(n, 0.0f);
  out.color_rgba.assign(n, 0);
  out.surface.assign(n, SurfaceCheck::kNoMeasurement);
  const auto* words = static_cast<const std::uint32_t*>(samples_out_.mapped());
  for (std::size_t i = 0; i < n; ++i) {
    std::memcpy(&out.depth_m[i], &words[2 * i], 4);
    out.hit[i] = (words[2 * i + 1] & gpu::kSampleHitBit) != 0 ? 1 : 0;
    out.color_rgba[i] = words[2 * i + 1] & 0xFFFFFFu;
    if ((words[2 * i + 1] & gpu::kSampleMeasuredBit) != 0) {
      const bool held = (words[2 * i + 1] & gpu::kSampleHeldBit) != 0;
      out.surface[i] = held ? SurfaceCheck::kHeld : SurfaceCheck::kNotHeld;
    }
  }
  return out;
}

}  // namespace strata
