// The topological map: build and incremental update (contract in topo_map.h).
#include "strata/plan/topo_map.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <unordered_set>

#include "strata/plan/internal/topo_boxes.h"
#include "strata/plan/internal/topo_links.h"
#include "strata/core/clock.h"

namespace strata::plan {
namespace {

using Clock = SteadyClock;

bool sameBox(const VoxelBox& a, const VoxelBox& b) { return a.lo == b.lo && a.hi == b.hi; }

VoxelBox intersect(const VoxelBox& a, const VoxelBox& b) {
  return VoxelBox{a.lo.cwiseMax(b.lo), a.hi.cwiseMin(b.hi)};
}

VoxelBox blockBox(const BlockIndex& b) {
  return VoxelBox{b * kBlockEdge, b * kBlockEdge + Eigen::Vector3i::Constant(kBlockEdge - 1)};
}

/// The blocks within `reach` blocks (Chebyshev) of a changed block.
std::vector<BlockIndex> dilateBlocks(const std::vector<BlockIndex>& blocks, int reach) {
  std::unordered_set<BlockIndex, BlockIndexHash> out;
  for (const BlockIndex& b : blocks) {
    for (int dz = -reach; dz <= reach; ++dz) {
      for (int dy = -reach; dy <= reach; ++dy) {
        for (int dx = -reach; dx <= reach; ++dx) out.insert(b + BlockIndex(dx, dy, dz));
      }
    }
  }
  return {out.begin(), out.end()};
}

}  // namespace

TopoMap::TopoMap(const EsdfMap& esdf, const TopoOptions& options) : options_(options) {
  build(esdf);
}

void TopoMap::build(const EsdfMap& esdf) {
  const auto start = Clock::now();
  voxel_size_m_ = esdf.voxel_size_m;
  bounds_ = allocatedBounds(esdf);
  HostCollisionChecker checker(esdf);
  const TraversabilityGrid grid(checker, bounds_, options_.radius_m, options_.unknown);
  std::vector<std::uint8_t> available(grid.cellCount(), 0);
  for (std::size_t i = 0; i < available.size(); ++i) {
    available[i] = grid.traversable(static_cast<std::int64_t>(i)) ? 1 : 0;
  }
  const std::vector<std::int64_t> seeds = seedsByClearance(esdf, bounds_, available);
  clusters_ = bounds_.empty() ? std::vector<VoxelBox>{} : growBoxes(bounds_, available, seeds);
  rebuildLinks();
  stats_.build_ms = msSince(start);
  stats_.traversable_voxels = grid.traversableCount();
  stats_.grid_cells = grid.cellCount();
}

void TopoMap::update(const EsdfMap& esdf, const std::vector<BlockIndex>& changed_blocks) {
  const auto start = Clock::now();
  stats_.clusters_dropped = stats_.clusters_grown = stats_.voxels_retested = 0;
  const VoxelBox new_bounds = allocatedBounds(esdf);
  if (!sameBox(new_bounds, bounds_) || esdf.voxel_size_m != voxel_size_m_) {
    build(esdf);
    stats_.last_update_full = true;
    stats_.voxels_retested = stats_.grid_cells;
    stats_.update_ms = msSince(start);
    return;
  }
  stats_.last_update_full = false;
  if (changed_blocks.empty()) {
    stats_.update_ms = msSince(start);
    return;
  }
  // A voxel's traversability reads the ESDF within the radius of it (plus its own voxel).
  const int reach_voxels = static_cast<int>(std::ceil(options_.radius_m / voxel_size_m_)) + 1;
  const std::vector<BlockIndex> dirty =
      dilateBlocks(changed_blocks, (reach_voxels + kBlockEdge - 1) / kBlockEdge);
  std::vector<std::uint8_t> drop(clusters_.size(), 0);
  for (const BlockIndex& b : dirty) {
    const auto it = block_clusters_.find(b);
    if (it == block_clusters_.end()) continue;
    for (std::int32_t c : it->second) drop[static_cast<std::size_t>(c)] = 1;
  }
  // The region to regrow: the dirty blocks and the dropped boxes, inside the bounds.
  VoxelBox region{Eigen::Vector3i::Constant(INT32_MAX), Eigen::Vector3i::Constant(INT32_MIN)};
  std::vector<VoxelBox> dirty_boxes;
  for (const BlockIndex& b : dirty) {
    const VoxelBox box = intersect(blockBox(b), bounds_);
    if (box.empty()) continue;
    dirty_boxes.push_back(box);
    region = VoxelBox{region.lo.cwiseMin(box.lo), region.hi.cwiseMax(box.hi)};
  }
  std::vector<VoxelBox> kept;
  std::vector<VoxelBox> dropped;
  for (std::size_t c = 0; c < clusters_.size(); ++c) {
    (drop[c] ? dropped : kept).push_back(clusters_[c]);
    if (drop[c]) {
      region = VoxelBox{region.lo.cwiseMin(clusters_[c].lo), region.hi.cwiseMax(clusters_[c].hi)};
    }
  }
  if (region.empty()) {
    stats_.update_ms = msSince(start);
    return;
  }
  std::vector<std::uint8_t> available(static_cast<std::size_t>(region.volume()), 0);
  const Eigen::Vector3i dims = region.hi - region.lo + Eigen::Vector3i::Ones();
  const auto cell = [&](const Eigen::Vector3i& v) {
    const Eigen::Vector3i l = v - region.lo;
    return static_cast<std::size_t>(l.x() +
                                    static_cast<std::int64_t>(dims.x()) *
                                        (l.y() + static_cast<std::int64_t>(dims.y()) * l.z()));
  };
  // Voxels of dropped boxes were traversable and stay so outside the dirty blocks.
  for (const VoxelBox& box : dropped) {
    for (int z = box.lo.z(); z <= box.hi.z(); ++z)
      for (int y = box.lo.y(); y <= box.hi.y(); ++y)
        for (int x = box.lo.x(); x <= box.hi.x(); ++x) available[cell({x, y, z})] = 1;
  }
  // In the dirty blocks: tested again (no kept box reaches into them).
  HostCollisionChecker checker(esdf);
  for (const VoxelBox& box : dirty_boxes) {
    const std::vector<std::uint8_t> free =
        sphereFreeInBox(checker, box, options_.radius_m, options_.unknown);
    std::size_t i = 0;
    for (int z = box.lo.z(); z <= box.hi.z(); ++z)
      for (int y = box.lo.y(); y <= box.hi.y(); ++y)
        for (int x = box.lo.x(); x <= box.hi.x(); ++x) available[cell({x, y, z})] = free[i++];
    stats_.voxels_retested += free.size();
  }
  const std::vector<VoxelBox> grown =
      growBoxes(region, available, seedsByClearance(esdf, region, available));
  stats_.clusters_dropped = dropped.size();
  stats_.clusters_grown = grown.size();
  stats_.traversable_voxels = 0;
  clusters_ = std::move(kept);
  clusters_.insert(clusters_.end(), grown.begin(), grown.end());
  for (const VoxelBox& box : clusters_)
    stats_.traversable_voxels += static_cast<std::size_t>(box.volume());
  rebuildLinks();
  stats_.update_ms = msSince(start);
}

void TopoMap::rebuildLinks() {
  TopoLinks links = linkClusters(clusters_, bounds_, voxel_size_m_);
  portals_ = std::move(links.portals);
  portal_offsets_ = std::move(links.portal_offsets);
  portal_ids_ = std::move(links.portal_ids);
  block_clusters_ = std::move(links.block_clusters);
  portal_centres_.clear();
  for (const TopoPortal& p : portals_) portal_centres_.push_back(p.centre());
  landmarks_ =
      TopoLandmarks(portals_, portal_centres_, portal_offsets_, portal_ids_, options_.landmarks);
}

const std::int32_t* TopoMap::portalsBegin(std::int32_t c) const {
  return portal_ids_.data() + portal_offsets_[static_cast<std::size_t>(c)];
}

const std::int32_t* TopoMap::portalsEnd(std::int32_t c) const {
  return portal_ids_.data() + portal_offsets_[static_cast<std::size_t>(c) + 1];
}

std::vector<float> TopoMap::distancesFrom(std::int32_t p) const {
  return portalDistances(portals_, portal_centres_, portal_offsets_, portal_ids_, p);
}

std::size_t TopoMap::edgeCount() const {
  std::size_t edges = 0;
  for (std::size_t c = 0; c < clusters_.size(); ++c) {
    const std::size_t k = static_cast<std::size_t>(portal_offsets_[c + 1] - portal_offsets_[c]);
    edges += k * (k - (k > 0 ? 1 : 0)) / 2;
  }
  return edges;
}

std::int32_t TopoMap::clusterAt(const Eigen::Vector3i& v) const {
  const auto it = block_clusters_.find(blockOfVoxel(v));
  if (it == block_clusters_.end()) return -1;
  for (std::int32_t c : it->second) {
    if (clusters_[static_cast<std::size_t>(c)].contains(v)) return c;
  }
  return -1;
}

std::vector<std::int32_t> TopoMap::components(std::int32_t* count) const {
  std::vector<std::int32_t> parent(clusters_.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](std::int32_t x) {
    while (parent[static_cast<std::size_t>(x)] != x) {
      parent[static_cast<std::size_t>(x)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
      x = parent[static_cast<std::size_t>(x)];
    }
    return x;
  };
  for (const TopoPortal& p : portals_) parent[static_cast<std::size_t>(find(p.a))] = find(p.b);
  std::vector<std::int32_t> label(clusters_.size(), -1);
  std::vector<std::int32_t> root_label(clusters_.size(), -1);
  std::int32_t next = 0;
  for (std::size_t c = 0; c < clusters_.size(); ++c) {
    const auto root = static_cast<std::size_t>(find(static_cast<std::int32_t>(c)));
    if (root_label[root] < 0) root_label[root] = next++;
    label[c] = root_label[root];
  }
  if (count != nullptr) *count = next;
  return label;
}

std::size_t TopoMap::memoryBytes() const {
  std::size_t bytes =
      clusters_.capacity() * sizeof(VoxelBox) + portals_.capacity() * sizeof(TopoPortal) +
      portal_centres_.capacity() * sizeof(Eigen::Vector3f) + landmarks_.memoryBytes() +
      (portal_offsets_.capacity() + portal_ids_.capacity()) * sizeof(std::int32_t);
  // The lookup: each entry's key, vector header and ids, plus a bucket pointer.
  for (const auto& [b, ids] : block_clusters_) {
    bytes += sizeof(BlockIndex) + sizeof(ids) + ids.capacity() * sizeof(std::int32_t) +
             2 * sizeof(void*);
  }
  return bytes + block_clusters_.bucket_count() * sizeof(void*);
}

}  // namespace strata::plan
