// Recording of an ESDF update on the device: per job, clear the working box, mark the sites
// (esdf_gather_sites), three exact 1-D transforms x, y, z (esdf_edt_pass), write the ESDF voxels
// of the updated blocks (esdf_scatter). All jobs go into one submission between two timestamps.
#include <algorithm>
#include <cstring>

#include "strata/map/device_layout.h"
#include "strata/esdf/internal/esdf_impl.h"
#include "strata/vk/dispatch_size.h"

namespace strata {
namespace {

using vk::kMaxGroupsPerDimension;
constexpr std::uint32_t kEdtLinesPerGroup = 64;     // esdf_edt_pass.comp local_size_x
constexpr std::uint32_t kNoSiteFill = 0xFFFFFFFFu;  // kEsdfNoSite in esdf_layout.glsl

void dispatchGroups(vk::CommandBuffer& cmd, std::uint32_t groups) {
  const std::uint32_t groups_x = std::min(groups, kMaxGroupsPerDimension);
  cmd.dispatch(groups_x, (groups + groups_x - 1) / groups_x);
}

/// Buffer of at least `bytes` (grown, never shrunk: updates of similar size reuse it).
void ensureBuffer(vk::Context& context, vk::Buffer& buffer, std::uint64_t bytes,
                  vk::MemoryUsage usage, const char* name) {
  if (buffer.valid() && buffer.size() >= bytes) return;
  buffer = vk::Buffer();  // release first: the old one may be large
  buffer = vk::Buffer::create(context, std::max<std::uint64_t>(bytes, 256), usage, name);
}

/// The lines of one axis pass (see esdf_edt_pass.comp) and how many there are. Only the lines
/// that later steps read are transformed: x over the whole box, y only where x lies in the update
/// box, z only where x and y do (the scatter reads update voxels only).
struct AxisLines {
  gpu::EsdfEdtPush push;
  std::uint32_t count;
};

AxisLines axisLines(const EsdfJob& job, std::uint32_t axis) {
  const Eigen::Vector3i dims = job.sites.sizeBlocks() * kBlockEdge;
  const Eigen::Vector3i update_min = (job.update.min - job.sites.min) * kBlockEdge;
  const Eigen::Vector3i update_size = job.update.sizeBlocks() * kBlockEdge;
  const auto u = [](int v) { return static_cast<std::uint32_t>(v); };
  const std::uint32_t nx = u(dims.x()), ny = u(dims.y()), nz = u(dims.z());
  gpu::EsdfEdtPush p{};
  p.axis = axis;
  std::uint32_t lines_b = 0;
  if (axis == 0) {  // a = y, b = z
    p.line_length = nx, p.stride_line = 1, p.stride_a = nx, p.stride_b = nx * ny;
    p.lines_a = ny, lines_b = nz;
  } else if (axis == 1) {  // a = x, b = z
    p.line_length = ny, p.stride_line = nx, p.stride_a = 1, p.stride_b = nx * ny;
    p.first_a = u(update_min.x()), p.lines_a = u(update_size.x()), lines_b = nz;
  } else {  // a = x, b = y
    p.line_length = nz, p.stride_line = nx * ny, p.stride_a = 1, p.stride_b = nx;
    p.first_a = u(update_min.x()), p.lines_a = u(update_size.x());
    p.first_b = u(update_min.y()), lines_b = u(update_size.y());
  }
  return AxisLines{p, p.lines_a * lines_b};
}

std::uint32_t linesPerDispatch(std::uint32_t line_length, std::uint64_t max_scratch_bytes) {
  const std::uint64_t lines = max_scratch_bytes / (std::uint64_t{line_length} * 8);
  return static_cast<std::uint32_t>(std::max<std::uint64_t>(lines, kEdtLinesPerGroup));
}

/// The descriptor sets of one submission (the buffers do not change while it is recorded).
struct JobSets {
  JobSets(vk::Context& context, const EsdfPipelines& p, const EsdfDeviceState& impl,
          DeviceTsdfMap& tsdf, int tsdf_layer)
      : gather(vk::DescriptorSet::create(context, p.gather,
                                         {&impl.lists, &impl.box, &tsdf.pool(tsdf_layer)})),
        edt(vk::DescriptorSet::create(context, p.edt, {&impl.box, &impl.scratch})),
        scatter(vk::DescriptorSet::create(context, p.scatter,
                                          {&impl.lists, &impl.box, &tsdf.pool(tsdf_layer), &impl.pool})) {}
  vk::DescriptorSet gather, edt, scatter;
};

struct JobRecorder {
  DeviceTsdfMap& tsdf;
  const EsdfConfig& config;
  EsdfDeviceState& impl;
  const EsdfPipelines& pipelines;
  const JobSets& sets;
  vk::CommandBuffer& cmd;

  gpu::EsdfBlockPush blockPush(const Eigen::Vector3i& dims, std::uint32_t first,
                               std::uint32_t count) const {
    const MapConfig& map = tsdf.config();
    gpu::EsdfBlockPush p{};
    p.box_address = impl.box.deviceAddress();
    p.tsdf_pool_address = tsdf.poolAddress(config.tsdf_layer);
    p.esdf_pool_address = impl.pool.deviceAddress();
    p.box_nx = static_cast<std::uint32_t>(dims.x());
    p.box_ny = static_cast<std::uint32_t>(dims.y());
    p.box_nz = static_cast<std::uint32_t>(dims.z());
    p.block_count = count;
    p.first_block = first;
    p.voxel_size_m = map.voxel_size_m;
    p.site_threshold_m = config.site_threshold_voxels * map.voxel_size_m;
    p.min_weight = config.min_weight;
    p.max_distance_m = config.max_distance_m;
    return p;
  }

  void blocks(const vk::ComputePipeline& pipeline, const vk::DescriptorSet& set,
              const gpu::EsdfBlockPush& push) {
    if (push.block_count == 0) return;
    cmd.bind(pipeline, set);
    cmd.pushConstants(pipeline, &push, sizeof(push));
    dispatchGroups(cmd, push.block_count);
    cmd.barrier();
  }

  void edtAxis(const EsdfJob& job, std::uint32_t axis) {
    const AxisLines axis_lines = axisLines(job, axis);
    gpu::EsdfEdtPush push = axis_lines.push;
    push.box_address = impl.box.deviceAddress();
    push.max_d2 = esdfReach(config, tsdf.config().voxel_size_m).max_d2;
    const std::uint32_t lines = axis_lines.count;
    const std::uint32_t chunk = linesPerDispatch(push.line_length, impl.max_scratch_bytes);
    cmd.bind(pipelines.edt, sets.edt);
    for (std::uint32_t first = 0; first < lines; first += chunk) {
      push.first_line = first;
      push.line_count = std::min(chunk, lines - first);
      cmd.pushConstants(pipelines.edt, &push, sizeof(push));
      dispatchGroups(cmd, (push.line_count + kEdtLinesPerGroup - 1) / kEdtLinesPerGroup);
      cmd.barrier();  // the next chunk reuses the scratch; the next axis reads the box
    }
  }

  void record(const EsdfJob& job, std::uint32_t gather_first, std::uint32_t scatter_first) {
    const Eigen::Vector3i dims = job.sites.sizeBlocks() * kBlockEdge;
    cmd.fill(impl.box, kNoSiteFill, 0, job.sites.voxelCount() * 4);
    cmd.barrier();
    blocks(pipelines.gather, sets.gather,
           blockPush(dims, gather_first, static_cast<std::uint32_t>(job.gather.size())));
    for (std::uint32_t axis = 0; axis < 3; ++axis) edtAxis(job, axis);
    blocks(pipelines.scatter, sets.scatter,
           blockPush(dims, scatter_first, static_cast<std::uint32_t>(job.scatter.size())));
  }
};

/// Working buffers for the largest job and all block lists, uploaded back to back.
std::vector<std::uint32_t> prepareBuffers(vk::Context& context, const std::vector<EsdfJob>& jobs,
                                          EsdfDeviceState& impl) {
  // The scratch is always reached through its binding: keep it within one binding's range.
  impl.max_scratch_bytes =
      std::min(impl.max_scratch_bytes, context.limits().max_storage_buffer_range_bytes);
  std::uint64_t box_voxels = 0, scratch_bytes = 0, listed = 0;
  for (const EsdfJob& job : jobs) {
    box_voxels = std::max(box_voxels, job.sites.voxelCount());
    const Eigen::Vector3i dims = job.sites.sizeBlocks() * kBlockEdge;
    for (int axis = 0; axis < 3; ++axis) {
      const auto n = static_cast<std::uint32_t>(dims[axis]);
      const std::uint64_t lines = job.sites.voxelCount() / n;
      scratch_bytes = std::max(
          scratch_bytes,
          std::min<std::uint64_t>(lines, linesPerDispatch(n, impl.max_scratch_bytes)) * n * 8);
    }
    listed += job.gather.size() + job.scatter.size();
  }
  ensureBuffer(context, impl.box, box_voxels * 4, vk::MemoryUsage::kDeviceLocal,
               "ESDF working box");
  ensureBuffer(context, impl.scratch, scratch_bytes, vk::MemoryUsage::kDeviceLocal, "ESDF scratch");
  ensureBuffer(context, impl.lists, listed * sizeof(ListedBlock), vk::MemoryUsage::kHostUpload,
               "ESDF block lists");
  std::vector<std::uint32_t> firsts;  // gather and scatter offsets per job
  auto* out = static_cast<ListedBlock*>(impl.lists.mapped());
  std::uint32_t at = 0;
  for (const EsdfJob& job : jobs) {
    for (const auto* list : {&job.gather, &job.scatter}) {
      firsts.push_back(at);
      if (!list->empty()) std::memcpy(out + at, list->data(), list->size() * sizeof(ListedBlock));
      at += static_cast<std::uint32_t>(list->size());
    }
  }
  return firsts;
}

/// Kernels that reach each buffer through a binding when it fits in one, else by device address.
const EsdfPipelines& pipelinesFor(vk::Context& context, DeviceTsdfMap& tsdf,
                                  EsdfDeviceState& impl) {
  const std::uint64_t range =
      std::min(context.limits().max_storage_buffer_range_bytes, impl.binding_limit_bytes);
  const bool box_by_address = impl.box.size() > range;
  const bool pools_by_address = tsdf.pool().size() > range || impl.pool.size() > range;
  auto& slot = impl.pipelines[(box_by_address ? 1 : 0) + (pools_by_address ? 2 : 0)];
  if (!slot) slot = std::make_unique<EsdfPipelines>(context, box_by_address, pools_by_address);
  return *slot;
}

}  // namespace

double runEsdfJobs(vk::Context& context, DeviceTsdfMap& tsdf, const EsdfConfig& config,
                   const std::vector<EsdfJob>& jobs, EsdfDeviceState& impl) {
  if (jobs.empty()) return 0.0;
  const std::vector<std::uint32_t> firsts = prepareBuffers(context, jobs, impl);
  const EsdfPipelines& pipelines = pipelinesFor(context, tsdf, impl);
  const JobSets sets(context, pipelines, impl, tsdf, config.tsdf_layer);
  vk::CommandBuffer cmd = vk::CommandBuffer::create(context);
  cmd.begin();
  cmd.resetQueries(impl.timer);
  cmd.writeTimestamp(impl.timer, 0);
  JobRecorder recorder{tsdf, config, impl, pipelines, sets, cmd};
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    recorder.record(jobs[j], firsts[2 * j], firsts[2 * j + 1]);
  }
  cmd.writeTimestamp(impl.timer, 1);
  cmd.end();
  cmd.submitAndWait();
  return impl.timer.elapsedMs(0, 1);
}

}  // namespace strata
