#include <algorithm>
#include <cstddef>
#include <cstring>
#include <optional>
#include <sstream>

#include "strata/core/error.h"
#include "strata/explore/internal/view_gain_rays.h"
#include "strata/explore/view_gain.h"
#include "strata/map/device_tsdf_map.h"
#include "strata/vk/dispatch_size.h"

namespace strata::explore {
namespace {

using internal::BlockBox;

/// Mirrors the push-constant block of shaders/explore/view_gain.comp.
struct ViewGainPush {
  std::uint64_t pool_address;
  float min_weight;
  float occupied_below_m;
  std::uint32_t position_offset;
  std::uint32_t position_count;
  std::uint32_t groups_y;
  std::uint32_t rays_per_position;
  std::uint32_t bin_rays;
  std::uint32_t yaw_bins;
  std::uint32_t steps;
  std::int32_t box_lo[3];
  std::int32_t box_n[3];
};
static_assert(sizeof(ViewGainPush) == 72 && offsetof(ViewGainPush, min_weight) == 8 &&
                  offsetof(ViewGainPush, box_lo) == 44 && offsetof(ViewGainPush, box_n) == 56,
              "ViewGainPush layout");

/// Mirrors the push-constant block of shaders/explore/view_gain_block_table.comp.
struct BlockTablePush {
  std::int32_t box_lo[3];
  std::int32_t box_n[3];
  std::uint32_t entry_count;
  std::uint32_t groups_x;
};
static_assert(sizeof(BlockTablePush) == 32, "BlockTablePush layout");

constexpr std::uint32_t kWorkgroupSize = 64;             // local_size_x of both shaders
using vk::kMaxGroupsPerDimension;
// A batch whose block box would exceed this goes in several chunks (16 MiB of table).
constexpr std::int64_t kMaxTableBlocks = std::int64_t{1} << 22;

/// A buffer holding `bytes` (at least 16), reallocated only when too small.
void ensureBuffer(vk::Context& context, vk::Buffer& buffer, std::size_t bytes,
                  vk::MemoryUsage usage, const char* name) {
  bytes = std::max<std::size_t>(bytes, 16);
  if (buffer.valid() && buffer.size() >= bytes) return;
  buffer =
      vk::Buffer::create(context, std::max<std::size_t>(bytes, 2 * buffer.size()), usage, name);
}

/// Consecutive positions [first, first + count) sharing one block table.
struct Chunk {
  std::size_t first = 0;
  std::size_t count = 0;
  BlockBox box;
};

std::vector<Chunk> chunksOf(const std::vector<internal::FixedPosition>& origins,
                            const internal::ViewGainRays& rays) {
  std::vector<Chunk> chunks;
  for (std::size_t i = 0; i < origins.size(); ++i) {
    const BlockBox box = internal::fanBlocks(origins[i], rays);
    if (!chunks.empty() && chunks.back().count < kMaxGroupsPerDimension &&
        chunks.back().box.merged(box).blocks() <= kMaxTableBlocks) {
      chunks.back().box = chunks.back().box.merged(box);
      ++chunks.back().count;
    } else {
      chunks.push_back({i, 1, box});
    }
  }
  return chunks;
}

}  // namespace

struct ViewGainKernel::Impl {
  explicit Impl(vk::Context& c) : context(c), timer(vk::TimestampQueries::create(c, 2)) {}

  const vk::ComputePipeline& gainPipeline(bool pool_by_address) {
    vk::ComputePipeline& p = gain_pipelines[pool_by_address ? 1 : 0];
    if (p.pipeline() == VK_NULL_HANDLE) {
      p = vk::ComputePipeline::create(context, "view_gain", 7, sizeof(ViewGainPush),
                                      {pool_by_address ? 1u : 0u});
    }
    return p;
  }

  const vk::ComputePipeline& tablePipeline() {
    if (table_pipeline.pipeline() == VK_NULL_HANDLE) {
      table_pipeline =
          vk::ComputePipeline::create(context, "view_gain_block_table", 2, sizeof(BlockTablePush));
    }
    return table_pipeline;
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

  /// Records the table pass and the gain pass of one chunk.
  void record(vk::CommandBuffer& cmd, DeviceTsdfMap& map, vk::Buffer& pool, const Chunk& chunk,
              const ViewGainPush& gain_push_base) {
    const Eigen::Vector3i n = chunk.box.hi - chunk.box.lo + Eigen::Vector3i::Ones();
    const std::size_t table_bytes = static_cast<std::size_t>(chunk.box.blocks()) * 4;
    cmd.fill(block_table, 0xFFFFFFFFu, 0, table_bytes);
    cmd.barrier();

    BlockTablePush table_push{};
    table_push.entry_count = map.hashCapacity();
    const std::uint32_t entry_groups =
        (table_push.entry_count + kWorkgroupSize - 1) / kWorkgroupSize;
    table_push.groups_x = std::min(entry_groups, kMaxGroupsPerDimension);
    ViewGainPush push = gain_push_base;
    for (int a = 0; a < 3; ++a) {
      table_push.box_lo[a] = push.box_lo[a] = chunk.box.lo[a];
      table_push.box_n[a] = push.box_n[a] = n[a];
    }
    const vk::ComputePipeline& table = tablePipeline();
    table_sets.push_back(
        vk::DescriptorSet::create(context, table, {&map.hashEntries(), &block_table}));
    cmd.bind(table, table_sets.back());
    cmd.pushConstants(table, &table_push, sizeof(table_push));
    cmd.dispatch(table_push.groups_x,
                 (entry_groups + table_push.groups_x - 1) / table_push.groups_x);
    cmd.barrier();

    const bool by_address = pool.size() > context.limits().max_storage_buffer_range_bytes;
    const vk::ComputePipeline& gain = gainPipeline(by_address);
    gain_sets.push_back(vk::DescriptorSet::create(
        context, gain,
        {&block_table, &ray_buffer, &step_t, &step_weight, &origins, &bin_units, &pool}));
    push.position_offset = static_cast<std::uint32_t>(chunk.first);
    push.position_count = static_cast<std::uint32_t>(chunk.count);
    push.groups_y = push.position_count;  // chunks hold at most 65535 positions
    cmd.bind(gain, gain_sets.back());
    cmd.pushConstants(gain, &push, sizeof(push));
    cmd.dispatch((push.rays_per_position + kWorkgroupSize - 1) / kWorkgroupSize, push.groups_y, 1);
    cmd.barrier();
  }

  vk::Context& context;
  vk::ComputePipeline gain_pipelines[2];
  vk::ComputePipeline table_pipeline;
  vk::TimestampQueries timer;
  std::optional<internal::ViewGainRays> rays;
  vk::Buffer ray_buffer, step_t, step_weight, origins, bin_units, block_table;
  std::vector<vk::DescriptorSet> table_sets, gain_sets;  // alive until the submission is done
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
  std::vector<internal::FixedPosition> fixed;
  fixed.reserve(positions_W.size());
  for (const Eigen::Vector3f& p : positions_W) {
    fixed.push_back(internal::fixedPosition(p, voxel_size_m));
  }
  if (fixed.empty()) return {};

  const std::size_t n = fixed.size();
  ensureBuffer(impl.context, impl.origins, n * 2 * sizeof(Eigen::Vector4i),
               vk::MemoryUsage::kHostUpload, "view gain origins");
  auto* origins = static_cast<Eigen::Vector4i*>(impl.origins.mapped());
  for (std::size_t i = 0; i < n; ++i) {
    origins[2 * i] = Eigen::Vector4i(fixed[i].voxel.x(), fixed[i].voxel.y(), fixed[i].voxel.z(), 0);
    origins[2 * i + 1] =
        Eigen::Vector4i(fixed[i].frac.x(), fixed[i].frac.y(), fixed[i].frac.z(), 0);
  }
  const std::size_t bin_bytes = n * config_.yaw_bins * sizeof(std::uint64_t);
  ensureBuffer(impl.context, impl.bin_units, bin_bytes, vk::MemoryUsage::kHostReadback,
               "view gain bins");
  const std::vector<Chunk> chunks = chunksOf(fixed, rays);
  std::int64_t table_blocks = 0;
  for (const Chunk& c : chunks) table_blocks = std::max(table_blocks, c.box.blocks());
  ensureBuffer(impl.context, impl.block_table, static_cast<std::size_t>(table_blocks) * 4,
               vk::MemoryUsage::kDeviceLocal, "view gain block table");

  ViewGainPush push{};
  vk::Buffer& pool = map.pool(config_.tsdf_layer);
  push.pool_address = pool.deviceAddress();
  push.min_weight = config_.min_weight;
  push.occupied_below_m = 0.5f * voxel_size_m;
  push.rays_per_position = static_cast<std::uint32_t>(rays.rays_per_position);
  push.bin_rays = static_cast<std::uint32_t>(rays.bin_rays);
  push.yaw_bins = static_cast<std::uint32_t>(config_.yaw_bins);
  push.steps = static_cast<std::uint32_t>(rays.steps);

  vk::CommandBuffer cmd = vk::CommandBuffer::create(impl.context);
  cmd.begin();
  cmd.fill(impl.bin_units, 0u, 0, bin_bytes);
  cmd.barrier();
  cmd.resetQueries(impl.timer);
  cmd.writeTimestamp(impl.timer, 0);
  for (const Chunk& chunk : chunks) impl.record(cmd, map, pool, chunk, push);
  cmd.writeTimestamp(impl.timer, 1);
  cmd.end();
  cmd.submitAndWait();
  impl.table_sets.clear();
  impl.gain_sets.clear();
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
