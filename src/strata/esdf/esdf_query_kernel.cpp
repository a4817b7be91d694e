#include "strata/esdf/esdf_query_kernel.h"

#include <algorithm>
#include <cstddef>

#include "strata/map/device_layout.h"
#include "strata/map/device_tsdf_map.h"
#include "strata/vk/timed_dispatch.h"
#include "strata/vk/dispatch_size.h"

namespace strata {
namespace {

/// Mirrors the push-constant block of shaders/esdf_query_points.comp.
struct EsdfQueryPush {
  std::uint64_t esdf_pool_address;
  std::uint64_t pool_address;
  std::uint32_t hash_mask;
  float voxel_size_m;
  float min_weight;
  std::uint32_t point_count;
  std::uint32_t esdf_block_count;
  float sphere_radius_m;
  float max_distance_m;
  std::uint32_t policy;
};
static_assert(sizeof(EsdfQueryPush) == 48 && offsetof(EsdfQueryPush, hash_mask) == 16 &&
                  offsetof(EsdfQueryPush, policy) == 44,
              "EsdfQueryPush layout");

constexpr std::uint32_t kWorkgroupSize = 128;            // local_size_x of the shader
using vk::kMaxGroupsPerDimension;
static_assert(kEsdfBlockBytes == 4096, "ESDF block stride in the shader");
// Non-finite points are sent as this: beyond the block range, so the shader reads them kOutside.
constexpr float kFarSentinel = 1e30f;

EsdfSample decode(const float* sample, std::uint32_t flags) {
  EsdfSample out;
  out.gradient = Eigen::Vector3f(sample[0], sample[1], sample[2]);
  out.distance_m = sample[3];
  out.status = static_cast<EsdfStatus>(flags & 3u);
  out.interpolated = (flags & 4u) != 0;
  return out;
}

}  // namespace

EsdfQueryKernel::EsdfQueryKernel(vk::Context& context)
    : context_(context),
      empty_pool_(vk::Buffer::create(context, kEsdfBlockBytes, vk::MemoryUsage::kDeviceLocal,
                                     "ESDF query empty pool")),
      timer_(vk::TimestampQueries::create(context, 2)) {}

const vk::ComputePipeline& EsdfQueryKernel::pipeline(bool pool_by_address) {
  vk::ComputePipeline& p = pipelines_[pool_by_address ? 1 : 0];
  if (p.pipeline() == VK_NULL_HANDLE) {
    p = vk::ComputePipeline::create(context_, "esdf_query_points", 5, sizeof(EsdfQueryPush),
                                    {pool_by_address ? 1u : 0u});
  }
  return p;
}

void EsdfQueryKernel::ensureCapacity(std::size_t points) {
  if (points <= capacity_) return;
  const std::size_t n = std::max<std::size_t>(points, 1024);
  points_ = vk::Buffer::create(context_, n * 16, vk::MemoryUsage::kHostUpload, "ESDF query points");
  samples_ =
      vk::Buffer::create(context_, n * 16, vk::MemoryUsage::kHostReadback, "ESDF query samples");
  flags_ = vk::Buffer::create(context_, n * 4, vk::MemoryUsage::kHostReadback, "ESDF query flags");
  capacity_ = n;
}

EsdfQueryResult EsdfQueryKernel::run(const DeviceEsdfView& esdf,
                                     const std::vector<Eigen::Vector3f>& points_W,
                                     const std::optional<EsdfSphereTest>& spheres) {
  EsdfQueryResult result;
  if (points_W.empty()) return result;
  ensureCapacity(points_W.size());
  auto* points = static_cast<float*>(points_.mapped());
  for (std::size_t i = 0; i < points_W.size(); ++i) {
    const bool finite = points_W[i].allFinite();
    for (int k = 0; k < 3; ++k) points[i * 4 + k] = finite ? points_W[i][k] : kFarSentinel;
    points[i * 4 + 3] = 0.0f;
  }

  const MapConfig& map_config = esdf.tsdf.config();
  EsdfQueryPush push{};
  push.esdf_pool_address = esdf.esdf_pool.deviceAddress();
  push.pool_address = esdf.tsdf.poolAddress();
  push.hash_mask = esdf.tsdf.hashMask();
  push.voxel_size_m = map_config.voxel_size_m;
  push.min_weight = esdf.config.min_weight;
  push.point_count = static_cast<std::uint32_t>(points_W.size());
  // Never past the pool's end, whatever the caller says.
  push.esdf_block_count = std::min<std::uint32_t>(
      esdf.computed_blocks, static_cast<std::uint32_t>(esdf.esdf_pool.size() / kEsdfBlockBytes));
  // NOTE: radius + margin is summed here, in float, exactly as EsdfQuery::isSphereFree does.
  push.sphere_radius_m = spheres ? spheres->radius_m + spheres->margin_m : -1.0f;
  // A NaN radius must fail the test, not skip it: send a value the shader refuses.
  if (spheres && !(push.sphere_radius_m >= 0.0f)) push.sphere_radius_m = kFarSentinel;
  push.max_distance_m = esdf.config.max_distance_m;
  push.policy = spheres ? static_cast<std::uint32_t>(spheres->policy) : 0u;

  // NOTE: a binding reaches only max_storage_buffer_range bytes; larger pools go by address.
  const bool has_pool = esdf.esdf_pool.valid() && push.esdf_block_count > 0;
  const bool by_address =
      has_pool && (force_pool_by_address_ ||
                   esdf.esdf_pool.size() > context_.limits().max_storage_buffer_range_bytes);
  const vk::ComputePipeline& pipe = pipeline(by_address);
  vk::DescriptorSet set =
      vk::DescriptorSet::create(context_, pipe,
                                {&esdf.tsdf.hashEntries(), &points_, &samples_, &flags_,
                                 has_pool ? &esdf.esdf_pool : &empty_pool_});
  const std::uint32_t groups = (push.point_count + kWorkgroupSize - 1) / kWorkgroupSize;
  const std::uint32_t groups_x = std::min(groups, kMaxGroupsPerDimension);
  result.device_ms = dispatchTimed(context_, pipe, set, &push, sizeof(push), groups_x,
                                   (groups + groups_x - 1) / groups_x, timer_);

  const auto* samples = static_cast<const float*>(samples_.mapped());
  const auto* flags = static_cast<const std::uint32_t*>(flags_.mapped());
  result.samples.reserve(points_W.size());
  for (std::size_t i = 0; i < points_W.size(); ++i) {
    result.samples.push_back(decode(samples + i * 4, flags[i]));
  }
  if (spheres) {
    result.sphere_free.resize(points_W.size());
    for (std::size_t i = 0; i < points_W.size(); ++i) result.sphere_free[i] = (flags[i] >> 3) & 1u;
  }
  return result;
}

}  // namespace strata
