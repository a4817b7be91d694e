#include "strata/raycast/raycast.h"

#include <cstring>

#include "strata/map/device_layout.h"
#include "strata/map/device_tsdf_map.h"
#include "strata/vk/timed_dispatch.h"

namespace strata {

RaycastKernel::RaycastKernel(vk::Context& context)
    : context_(context),
      pipeline_(vk::ComputePipeline::create(context, "raycast_tsdf", 4, sizeof(gpu::RaycastPush))),
      timer_(vk::TimestampQueries::create(context, 2)) {}

void RaycastKernel::ensureOutputs(std::size_t pixel_count) {
  if (pixel_count <= pixel_capacity_) return;
  depth_out_ = vk::Buffer::create(context_, pixel_count * 4, vk::MemoryUsage::kHostReadback,
                                  "raycast depth");
  normal_out_ = vk::Buffer::create(context_, pixel_count * 16, vk::MemoryUsage::kHostReadback,
                                   "raycast normals");
  color_out_ = vk::Buffer::create(context_, pixel_count * 4, vk::MemoryUsage::kHostReadback,
                                  "raycast colour");
  pixel_capacity_ = pixel_count;
}

double RaycastKernel::render(DeviceTsdfMap& map, const CameraIntrinsics& intrinsics,
                             const Eigen::Isometry3d& T_W_C, const RaycastOptions& options) {
  intrinsics.validate();
  validatePose(T_W_C, "raycast camera");
  const FrameCamera camera = FrameCamera::from(intrinsics, T_W_C);
  const std::size_t pixels = static_cast<std::size_t>(intrinsics.width_px) * intrinsics.height_px;
  ensureOutputs(pixels);

  const MapConfig& config = map.config();
  gpu::RaycastPush push{};
  gpu::storeMatrix(camera.T_W_C, push.T_W_C);
  for (int i = 0; i < 4; ++i) push.K[i] = camera.K[i];
  push.image_size[0] = static_cast<std::uint32_t>(intrinsics.width_px);
  push.image_size[1] = static_cast<std::uint32_t>(intrinsics.height_px);
  push.min_depth_m = config.min_depth_m;
  push.max_depth_m = config.max_depth_m;
  push.voxel_size_m = config.voxel_size_m;
  push.truncation_m = config.truncationDistance();
  push.hash_mask = map.hashMask();
  push.min_weight = options.min_weight;
  push.pool_address = map.poolAddress(options.tsdf_layer);
  push.max_steps = options.max_steps;

  vk::DescriptorSet set = vk::DescriptorSet::create(
      context_, pipeline_, {&map.hashEntries(), &depth_out_, &normal_out_, &color_out_});
  return dispatchTimed(context_, pipeline_, set, &push, sizeof(push),
                       (push.image_size[0] + 15) / 16, (push.image_size[1] + 15) / 16, timer_);
}

RaycastImage RaycastKernel::run(DeviceTsdfMap& map, const CameraIntrinsics& intrinsics,
                                const Eigen::Isometry3d& T_W_C, const RaycastOptions& options,
                                double* device_ms) {
  const double ms = render(map, intrinsics, T_W_C, options);
  if (device_ms != nullptr) *device_ms = ms;
  const std::size_t pixels = static_cast<std::size_t>(intrinsics.width_px) * intrinsics.height_px;

  RaycastImage out{DepthImage(intrinsics.width_px, intrinsics.height_px),
                   std::vector<Eigen::Vector3f>(pixels, Eigen::Vector3f::Zero()),
                   ColorImage(intrinsics.width_px, intrinsics.height_px),
                   std::vector<std::uint8_t>(pixels, 0)};
  std::memcpy(out.depth.depth_m.data(), depth_out_.mapped(), pixels * 4);
  const auto* normals = static_cast<const float*>(normal_out_.mapped());
  const auto* colors = static_cast<const std::uint32_t*>(color_out_.mapped());
  for (std::size_t i = 0; i < pixels; ++i) {
    out.hit[i] = normals[i * 4 + 3] > 0.5f ? 1 : 0;
    out.normal_W[i] = Eigen::Vector3f(normals[i * 4], normals[i * 4 + 1], normals[i * 4 + 2]);
    for (int c = 0; c < 3; ++c) out.color.rgb[i * 3 + c] = (colors[i] >> (8 * c)) & 255u;
  }
  return out;
}

}  // namespace strata
