#include "strata/occupancy/occupancy_reference.h"

#include <unordered_set>

#include "strata/core/error.h"

namespace strata {
namespace {

/// The scan's marks (mark pass) and the blocks holding any, so the update visits only those.
class ScanMarks {
 public:
  explicit ScanMarks(OccupancyMap& map) : map_(map) {}

  void mark(const GlobalVoxelIndex& voxel, std::uint32_t bit) {
    const BlockIndex b = blockOfVoxel(voxel);
    if (block_ == nullptr || b != block_index_) {  // rays stay in a block for several voxels
      block_index_ = b;
      block_ = &map_.allocateBlock(b);  // unordered_map nodes: the pointer survives rehashing
      touched_.insert(b);
    }
    const Eigen::Vector3i local = voxel - b * kBlockEdge;
    (*block_)[linearVoxelIndex(local.x(), local.y(), local.z())].state |= bit;
  }
  const std::unordered_set<BlockIndex, BlockIndexHash>& touched() const { return touched_; }

 private:
  OccupancyMap& map_;
  BlockIndex block_index_ = BlockIndex::Zero();
  OccupancyBlock* block_ = nullptr;
  std::unordered_set<BlockIndex, BlockIndexHash> touched_;
};

/// One ray (occupancy_mark.comp): misses on the way, the hit at the endpoint.
void markRay(const OccupancyRayEnds& ends, ScanMarks& marks) {
  OccupancyVoxelRay ray(ends);
  while (!ray.atEnd()) {
    marks.mark(ray.voxel(), kOccupancyMissThisScan);
    ray.advance();
  }
  if (ends.hit) marks.mark(ray.voxel(), kOccupancyHitThisScan);
}

/// occupancy_update.comp: one update per marked voxel.
std::uint64_t applyMarks(const ScanMarks& marks, const OccupancyLogOdds& l, OccupancyMap& map) {
  std::uint64_t updated = 0;
  for (const BlockIndex& b : marks.touched()) {
    for (OccupancyVoxel& v : *map.findBlock(b)) {
      if ((v.state & kOccupancyScanBits) == 0u) continue;
      v.log_odds = occupancyUpdate(v.state, v.log_odds, l);
      v.state = occupancyStateAfterUpdate(v.state);
      ++updated;
    }
  }
  return updated;
}

}  // namespace

OccupancyRayCamera occupancyRayCamera(const FrameCamera& camera, const OccupancyConfig& config,
                                      float voxel_size_m) {
  OccupancyRayCamera c;
  for (int i = 0; i < 16; ++i) c.T_W_C[i] = camera.T_W_C.data()[i];  // Eigen: column-major
  c.K_inv[0] = 1.0f / camera.K[0];
  c.K_inv[1] = 1.0f / camera.K[1];
  c.K_inv[2] = camera.K[2];
  c.K_inv[3] = camera.K[3];
  c.min_depth_m = config.min_depth_m;
  c.max_range_m = config.max_range_m;
  c.inv_voxel_size = 1.0f / voxel_size_m;
  return c;
}

OccupancyScanCounts integrateOccupancyReference(const DepthImage& depth, const FrameCamera& camera,
                                                const OccupancyConfig& config, OccupancyMap& map) {
  config.validate();
  if (depth.width_px != camera.width_px || depth.height_px != camera.height_px) {
    throw InputError("occupancy reference: depth image size does not match the camera");
  }
  const OccupancyRayCamera c = occupancyRayCamera(camera, config, map.voxelSize());
  const int stride = static_cast<int>(config.pixel_stride);
  OccupancyScanCounts counts;
  ScanMarks marks(map);
  for (int v = 0; v < depth.height_px; v += stride) {
    for (int u = 0; u < depth.width_px; u += stride) {
      OccupancyRayEnds ends;
      if (!occupancyRayEnds(static_cast<float>(u), static_cast<float>(v), depth.at(u, v), c,
                            ends)) {
        continue;
      }
      markRay(ends, marks);
      ++counts.rays;
    }
  }
  counts.updated_voxels = applyMarks(marks, config.logOdds(), map);
  return counts;
}

}  // namespace strata
