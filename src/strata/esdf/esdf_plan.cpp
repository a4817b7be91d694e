#include "strata/esdf/esdf_plan.h"

#include <algorithm>
#include <sstream>

#include "strata/core/error.h"

namespace strata {
namespace {

std::string describeBox(const BlockBox& box) {
  const Eigen::Vector3i voxels = box.sizeBlocks() * kBlockEdge;
  std::ostringstream text;
  text << voxels.x() << " x " << voxels.y() << " x " << voxels.z() << " voxels ("
       << box.voxelCount() * 4 / (1 << 20) << " MiB)";
  return text.str();
}

/// The update box cut into slabs along its longest axis, each thin enough that its site box fits.
std::vector<BlockBox> slabs(const BlockBox& update, const BlockBox& map_box, int reach_blocks,
                            std::uint64_t max_box_voxels) {
  const BlockBox whole_sites = update.dilated(reach_blocks).intersected(map_box);
  if (whole_sites.voxelCount() <= max_box_voxels) return {update};
  int axis = 0;
  update.sizeBlocks().maxCoeff(&axis);
  // Voxels per block-thick layer of the site box across the cut axis.
  const std::uint64_t layer =
      whole_sites.voxelCount() / static_cast<std::uint64_t>(whole_sites.sizeBlocks()[axis]);
  const auto layers = static_cast<std::int64_t>(max_box_voxels / layer);
  const std::int64_t thickness = layers - 2 * reach_blocks;
  if (thickness < 1) {
    throw DeviceError("ESDF working box too large: the update needs " + describeBox(whole_sites) +
                      " and even a one-block slab of it (with the " + std::to_string(reach_blocks) +
                      "-block margin for sites) exceeds the " +
                      std::to_string(max_box_voxels * 4 >> 20) +
                      " MiB working budget; use a larger voxel size or a smaller max distance");
  }
  std::vector<BlockBox> out;
  for (int start = update.min[axis]; start <= update.max[axis];
       start += static_cast<int>(thickness)) {
    BlockBox slab = update;
    slab.min[axis] = start;
    slab.max[axis] =
        static_cast<int>(std::min<std::int64_t>(update.max[axis], start + thickness - 1));
    out.push_back(slab);
  }
  return out;
}

ListedBlock listed(const BlockIndex& b, const BlockBox& box, std::uint32_t slot) {
  const Eigen::Vector3i rel = b - box.min;
  return ListedBlock{rel.x(), rel.y(), rel.z(), slot};
}

}  // namespace

void BlockBox::include(const BlockIndex& b) {
  if (empty()) {
    min = max = b;
    return;
  }
  min = min.cwiseMin(b);
  max = max.cwiseMax(b);
}

BlockBox BlockBox::dilated(int blocks) const {
  if (empty()) return *this;
  return BlockBox{min - Eigen::Vector3i::Constant(blocks), max + Eigen::Vector3i::Constant(blocks)};
}

BlockBox BlockBox::intersected(const BlockBox& other) const {
  return BlockBox{min.cwiseMax(other.min), max.cwiseMin(other.max)};
}

std::uint64_t BlockBox::voxelCount() const {
  const Eigen::Vector3i s = sizeBlocks();
  return static_cast<std::uint64_t>(s.x()) * s.y() * s.z() * kVoxelsPerBlock;
}

std::vector<EsdfJob> planEsdfJobs(const BlockBox& update, const BlockBox& map_box, int reach_blocks,
                                  const std::vector<BlockIndex>& slot_blocks,
                                  std::uint64_t max_box_voxels) {
  std::vector<EsdfJob> jobs;
  const BlockBox clipped = update.intersected(map_box);
  if (clipped.empty()) return jobs;
  for (const BlockBox& slab : slabs(clipped, map_box, reach_blocks, max_box_voxels)) {
    EsdfJob job;
    job.update = slab;
    job.sites = slab.dilated(reach_blocks).intersected(map_box);
    for (std::size_t s = 0; s < slot_blocks.size(); ++s) {
      const BlockIndex& b = slot_blocks[s];
      if (!job.sites.contains(b)) continue;
      const auto slot = static_cast<std::uint32_t>(s);
      job.gather.push_back(listed(b, job.sites, slot));
      if (job.update.contains(b)) job.scatter.push_back(listed(b, job.sites, slot));
    }
    if (!job.scatter.empty()) jobs.push_back(std::move(job));
  }
  return jobs;
}

}  // namespace strata
