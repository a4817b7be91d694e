// Greedy box growing for the topological map (contract in topo_boxes.h).
#include "strata/plan/internal/topo_boxes.h"

#include <algorithm>

namespace strata::plan {
namespace {

/// Dense indexing of a region's cells (x fastest).
struct RegionIndex {
  Eigen::Vector3i lo;
  Eigen::Vector3i dims;
  explicit RegionIndex(const VoxelBox& region)
      : lo(region.lo), dims(region.hi - region.lo + Eigen::Vector3i::Ones()) {}
  std::int64_t operator()(const Eigen::Vector3i& v) const {
    const Eigen::Vector3i l = v - lo;
    return l.x() + static_cast<std::int64_t>(dims.x()) *
                       (l.y() + static_cast<std::int64_t>(dims.y()) * l.z());
  }
  Eigen::Vector3i voxel(std::int64_t i) const {
    return lo + Eigen::Vector3i(
                    static_cast<int>(i % dims.x()), static_cast<int>(i / dims.x() % dims.y()),
                    static_cast<int>(i / (static_cast<std::int64_t>(dims.x()) * dims.y())));
  }
};

template <typename Visit>
void forEachVoxel(const VoxelBox& box, Visit visit) {
  for (int z = box.lo.z(); z <= box.hi.z(); ++z) {
    for (int y = box.lo.y(); y <= box.hi.y(); ++y) {
      for (int x = box.lo.x(); x <= box.hi.x(); ++x) {
        if (!visit(Eigen::Vector3i(x, y, z))) return;
      }
    }
  }
}

/// The layer just outside `box` in direction `dir` (axis dir / 2, sign + for even dir).
VoxelBox faceLayer(const VoxelBox& box, int dir) {
  const int axis = dir / 2;
  VoxelBox layer = box;
  if (dir % 2 == 0) {
    layer.lo[axis] = layer.hi[axis] = box.hi[axis] + 1;
  } else {
    layer.lo[axis] = layer.hi[axis] = box.lo[axis] - 1;
  }
  return layer;
}

bool layerAvailable(const VoxelBox& layer, const VoxelBox& region, const RegionIndex& index,
                    const std::vector<std::uint8_t>& available) {
  if (!region.contains(layer.lo) || !region.contains(layer.hi)) return false;
  bool all = true;
  forEachVoxel(layer, [&](const Eigen::Vector3i& v) {
    all = available[static_cast<std::size_t>(index(v))] != 0;
    return all;
  });
  return all;
}

VoxelBox growOne(const Eigen::Vector3i& seed, const VoxelBox& region, const RegionIndex& index,
                 const std::vector<std::uint8_t>& available) {
  VoxelBox box{seed, seed};
  bool open[6] = {true, true, true, true, true, true};
  for (bool grew = true; grew;) {
    grew = false;
    for (int dir = 0; dir < 6; ++dir) {
      if (!open[dir]) continue;
      const VoxelBox layer = faceLayer(box, dir);
      if (!layerAvailable(layer, region, index, available)) {
        open[dir] = false;
        continue;
      }
      box.lo = box.lo.cwiseMin(layer.lo);
      box.hi = box.hi.cwiseMax(layer.hi);
      grew = true;
    }
  }
  return box;
}

}  // namespace

std::vector<VoxelBox> growBoxes(const VoxelBox& region, std::vector<std::uint8_t>& available,
                                const std::vector<std::int64_t>& seeds) {
  const RegionIndex index(region);
  std::vector<VoxelBox> boxes;
  for (std::int64_t seed : seeds) {
    if (available[static_cast<std::size_t>(seed)] == 0) continue;
    const VoxelBox box = growOne(index.voxel(seed), region, index, available);
    forEachVoxel(box, [&](const Eigen::Vector3i& v) {
      available[static_cast<std::size_t>(index(v))] = 0;
      return true;
    });
    boxes.push_back(box);
  }
  return boxes;
}

std::vector<std::int64_t> seedsByClearance(const EsdfMap& esdf, const VoxelBox& region,
                                           const std::vector<std::uint8_t>& available) {
  const RegionIndex index(region);
  std::vector<std::pair<float, std::int64_t>> keyed;
  for (std::size_t i = 0; i < available.size(); ++i) {
    if (available[i] == 0) continue;
    const EsdfVoxel* v = esdf.findVoxel(index.voxel(static_cast<std::int64_t>(i)));
    const float clearance_m = v != nullptr && esdfObserved(*v) ? v->distance_m : 0.0f;
    keyed.emplace_back(-clearance_m, static_cast<std::int64_t>(i));
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::int64_t> seeds;
  seeds.reserve(keyed.size());
  for (const auto& [key, i] : keyed) seeds.push_back(i);
  return seeds;
}

}  // namespace strata::plan
