#include <algorithm>
#include <cstddef>
#include <cstring>
#include <optional>
#include <sstream>

#include "core/error.h"
#include "explore/internal/view_gain_rays.h"
#include "explore/view_gain.h"
#include "map/device_layout.h"
#include "map/device_tsdf_map.h"

namespace strata::explore {
namespace {

/// Mirrors the push-constant block of shaders/explore/view_gain.comp.
struct ViewGainPush {
  std::uint64_t pool_address;
  std::uint32_t hash_mask;
  float voxel_size_m;
  float min_weight;
  float occupied_below_m;
  std::uint32_t position_offset;
  std::uint32_t position_count;
  std::uint32_t groups_y;
  std::uint32_t rays_per_position;
  std::uint32_t bin_rays;
  std::uint32_t yaw_bins;
  std::uint32_t steps;
  std::uint32_t pad0;
};
static_assert(sizeof(ViewGainPush) == 56 && offsetof(ViewGainPush, hash_mask) == 8 &&
                  offsetof(ViewGainPush, steps) == 48,
              "ViewGainPush layout");

constexpr std::uint32_t kWorkgroupSize = 64;             // local_size_x of the shader
constexpr std::uint32_t kMaxGroupsPerDimension = 65535;  // Vulkan's guaranteed minimum
// Positions per dispatch: y and z both within the limit.
constexpr std::uint64_t kMaxPositionsPerDispatch =
    std::uint64_t{kMaxGroupsPerDimension} * kMaxGroupsPerDimension;

/// A host-upload buffer holding `bytes` (at least 16), reallocated only when too small.
void ensureBuffer(vk::Context& context, vk::Buffer& buffer, std::size_t bytes,
                  vk::MemoryUsage usage, const char* name) {
  bytes = std::max<std::size_t>(bytes, 16);
  if (buffer.valid() && buffer.size() >= bytes) return;
  buffer =
      vk::Buffer::create(context, std::max<std::size_t>(bytes, 2 * buffer.size()), usage, name);
}

}  // namespace

struct ViewGainKernel::Impl {
  explicit Impl(vk::Context& c) : context(c), timer(vk::TimestampQueries::create(c, 2)) {}

  const vk::ComputePipeline& pipeline(bool pool_by_address) {
    vk::ComputePipeline& p = pipelines[pool_by_address ? 1 : 0];
    if (p.pipeline() == VK_NULL_HANDLE) {
      p = vk::ComputePipeline::create(context, "view_gain", 7, sizeof(ViewGainPush),
                                      {pool_by_address ? 1u : 0u});
    }
    return p;
  }

  /// The ray tables for this voxel size on the device (rebuilt when it changes).
  void prepareRays(const ViewGainConfig& config, float voxel_size_m) {
    if (rays && rays->voxel_size_m == voxel_size_m) return;
    rays = internal::makeViewGainRays(config, voxel_size_m);
    const auto upload = [&](vk::Buffer& buffer, const void* data, std::size_t bytes,
                            const char* name) {
      ensureBuffer(context, buffer, bytes, vk::MemoryUsage::kHostUpload, name);
      std::memcpy(buffer.mapped(), data, bytes);
    };
    upload(ray_buffer, rays->dir_q.data(), rays->dir_q.size() * sizeof(Eigen::Vector4i),
           "view gain rays");
    upload(step_t, rays->t_q.data(), rays->t_q.size() * sizeof(std::int32_t), "view gain steps");
    upload(step_weight, rays->weight.data(), rays->weight.size() * sizeof(std::uint32_t),
           "view gain weights");
  }

  vk::Context& context;
  vk::ComputePipeline pipelines[2];
  vk::TimestampQueries timer;
  std::optional<internal::ViewGainRays> rays;
  vk::Buffer ray_buffer, step_t, step_weight, origins, bin_units;
};

ViewGainKernel::ViewGainKernel(vk::Context& context, const ViewGainConfig& config)
    : impl_(std::make_shared<Impl>(context)), config_(config) {
  config_.validate();
}

std::vector<ViewGain> ViewGainKernel::run(DeviceTsdfMap& map,
                                          const std::vector<Eigen::Vector3f>& positions_W,
                                          double* device_ms) {
  if (device_ms != nullptr) *device_ms = 0.0;
  if (config_.tsdf_layer >= map.tsdfLayerCount()) {
    std::ostringstream message;
    message << "ViewGainConfig.tsdf_layer " << config_.tsdf_layer << ": the map has "
            << map.tsdfLayerCount() << " TSDF layers";
    throw InputError(message.str());
  }
  Impl& impl = *impl_;
  const float voxel_size_m = map.config().voxel_size_m;
  impl.prepareRays(config_, voxel_size_m);
  const internal::ViewGainRays& rays = *impl.rays;
  if (positions_W.empty()) return {};
  if (positions_W.size() > kMaxPositionsPerDispatch) {
    throw InputError("ViewGainKernel::run: too many positions for one dispatch");
  }

  const std::size_t n = positions_W.size();
  ensureBuffer(impl.context, impl.origins, n * 2 * sizeof(Eigen::Vector4i),
               vk::MemoryUsage::kHostUpload, "view gain origins");
  auto* origins = static_cast<Eigen::Vector4i*>(impl.origins.mapped());
  for (std::size_t i = 0; i < n; ++i) {
    const internal::FixedPosition p = internal::fixedPosition(positions_W[i], voxel_size_m);
    origins[2 * i] = Eigen::Vector4i(p.voxel.x(), p.voxel.y(), p.voxel.z(), 0);
    origins[2 * i + 1] = Eigen::Vector4i(p.frac.x(), p.frac.y(), p.frac.z(), 0);
  }
  const std::size_t bin_bytes = n * config_.yaw_bins * sizeof(std::uint64_t);
  ensureBuffer(impl.context, impl.bin_units, bin_bytes, vk::MemoryUsage::kHostReadback,
               "view gain bins");

  vk::Buffer& pool = map.pool(config_.tsdf_layer);
  const bool by_address = pool.size() > impl.context.limits().max_storage_buffer_range_bytes;
  const vk::ComputePipeline& pipe = impl.pipeline(by_address);
  vk::DescriptorSet set =
      vk::DescriptorSet::create(impl.context, pipe,
                                {&map.hashEntries(), &impl.ray_buffer, &impl.step_t,
                                 &impl.step_weight, &impl.origins, &impl.bin_units, &pool});

  ViewGainPush push{};
  push.pool_address = pool.deviceAddress();
  push.hash_mask = map.hashMask();
  push.voxel_size_m = voxel_size_m;
  push.min_weight = config_.min_weight;
  push.occupied_below_m = 0.5f * voxel_size_m;
  push.position_offset = 0;
  push.position_count = static_cast<std::uint32_t>(n);
  push.groups_y = static_cast<std::uint32_t>(std::min<std::size_t>(n, kMaxGroupsPerDimension));
  push.rays_per_position = static_cast<std::uint32_t>(rays.rays_per_position);
  push.bin_rays = static_cast<std::uint32_t>(rays.bin_rays);
  push.yaw_bins = static_cast<std::uint32_t>(config_.yaw_bins);
  push.steps = static_cast<std::uint32_t>(rays.steps);
  const std::uint32_t groups_x = (push.rays_per_position + kWorkgroupSize - 1) / kWorkgroupSize;
  const std::uint32_t groups_z =
      static_cast<std::uint32_t>((n + push.groups_y - 1) / push.groups_y);

  vk::CommandBuffer cmd = vk::CommandBuffer::create(impl.context);
  cmd.begin();
  cmd.fill(impl.bin_units, 0u, 0, bin_bytes);
  cmd.barrier();
  cmd.resetQueries(impl.timer);
  cmd.writeTimestamp(impl.timer, 0);
  cmd.bind(pipe, set);
  cmd.pushConstants(pipe, &push, sizeof(push));
  cmd.dispatch(groups_x, push.groups_y, groups_z);
  cmd.barrier();
  cmd.writeTimestamp(impl.timer, 1);
  cmd.end();
  cmd.submitAndWait();
  if (device_ms != nullptr) *device_ms = impl.timer.elapsedMs(0, 1);

  const auto* units = static_cast<const std::uint64_t*>(impl.bin_units.mapped());
  std::vector<ViewGain> gains;
  gains.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    gains.push_back(internal::finishViewGain(units + i * config_.yaw_bins, rays, config_));
  }
  return gains;
}

}  // namespace strata::explore
