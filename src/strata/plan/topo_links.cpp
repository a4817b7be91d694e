// Portals and lookups of the topological map (contract in topo_links.h).
#include "strata/plan/internal/topo_links.h"

#include <algorithm>

namespace strata::plan {
namespace {

/// Cluster id per cell of `bounds` (x fastest), -1 where none.
struct ClusterGrid {
  VoxelBox bounds;
  Eigen::Vector3i dims;
  std::vector<std::int32_t> id;

  ClusterGrid(const std::vector<VoxelBox>& boxes, const VoxelBox& b)
      : bounds(b),
        dims(b.hi - b.lo + Eigen::Vector3i::Ones()),
        id(static_cast<std::size_t>(b.volume()), -1) {
    for (std::size_t c = 0; c < boxes.size(); ++c) {
      const VoxelBox& box = boxes[c];
      for (int z = box.lo.z(); z <= box.hi.z(); ++z)
        for (int y = box.lo.y(); y <= box.hi.y(); ++y)
          for (int x = box.lo.x(); x <= box.hi.x(); ++x) {
            id[index({x, y, z})] = static_cast<std::int32_t>(c);
          }
    }
  }
  std::size_t index(const Eigen::Vector3i& v) const {
    const Eigen::Vector3i l = v - bounds.lo;
    return static_cast<std::size_t>(l.x() +
                                    static_cast<std::int64_t>(dims.x()) *
                                        (l.y() + static_cast<std::int64_t>(dims.y()) * l.z()));
  }
};

/// The clusters touching `box` across its upper face along `axis`.
std::vector<std::int32_t> upperNeighbours(const ClusterGrid& grid, const VoxelBox& box, int axis) {
  std::vector<std::int32_t> out;
  VoxelBox layer = box;
  layer.lo[axis] = layer.hi[axis] = box.hi[axis] + 1;
  if (layer.lo[axis] > grid.bounds.hi[axis]) return out;
  for (int z = layer.lo.z(); z <= layer.hi.z(); ++z)
    for (int y = layer.lo.y(); y <= layer.hi.y(); ++y)
      for (int x = layer.lo.x(); x <= layer.hi.x(); ++x) {
        const std::int32_t c = grid.id[grid.index({x, y, z})];
        if (c >= 0 && (out.empty() || out.back() != c)) out.push_back(c);
      }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

TopoPortal makePortal(const std::vector<VoxelBox>& boxes, std::int32_t a, std::int32_t b, int axis,
                      float voxel_size_m) {
  const VoxelBox& A = boxes[static_cast<std::size_t>(a)];
  const VoxelBox& B = boxes[static_cast<std::size_t>(b)];
  TopoPortal p;
  p.a = a;
  p.b = b;
  p.axis = axis;
  const Eigen::Vector3i lo = A.lo.cwiseMax(B.lo), hi = A.hi.cwiseMin(B.hi);
  p.lo_W = (lo.cast<float>() + Eigen::Vector3f::Constant(0.5f)) * voxel_size_m;
  p.hi_W = (hi.cast<float>() + Eigen::Vector3f::Constant(0.5f)) * voxel_size_m;
  // On the plane between A's last layer and B's first.
  p.lo_W[axis] = p.hi_W[axis] = static_cast<float>(A.hi[axis] + 1) * voxel_size_m;
  return p;
}

}  // namespace

TopoLinks linkClusters(const std::vector<VoxelBox>& boxes, const VoxelBox& bounds,
                       float voxel_size_m) {
  TopoLinks links;
  links.portal_offsets.assign(boxes.size() + 1, 0);
  if (boxes.empty()) return links;
  const ClusterGrid grid(boxes, bounds);
  for (std::size_t a = 0; a < boxes.size(); ++a) {
    for (int axis = 0; axis < 3; ++axis) {
      for (std::int32_t b : upperNeighbours(grid, boxes[a], axis)) {
        links.portals.push_back(
            makePortal(boxes, static_cast<std::int32_t>(a), b, axis, voxel_size_m));
      }
    }
  }
  for (const TopoPortal& p : links.portals) {
    ++links.portal_offsets[static_cast<std::size_t>(p.a) + 1];
    ++links.portal_offsets[static_cast<std::size_t>(p.b) + 1];
  }
  for (std::size_t c = 0; c < boxes.size(); ++c)
    links.portal_offsets[c + 1] += links.portal_offsets[c];
  links.portal_ids.assign(static_cast<std::size_t>(links.portal_offsets.back()), -1);
  std::vector<std::int32_t> fill(links.portal_offsets.begin(), links.portal_offsets.end() - 1);
  for (std::size_t i = 0; i < links.portals.size(); ++i) {
    const TopoPortal& p = links.portals[i];
    links.portal_ids[static_cast<std::size_t>(fill[static_cast<std::size_t>(p.a)]++)] =
        static_cast<std::int32_t>(i);
    links.portal_ids[static_cast<std::size_t>(fill[static_cast<std::size_t>(p.b)]++)] =
        static_cast<std::int32_t>(i);
  }
  for (std::size_t c = 0; c < boxes.size(); ++c) {
    const BlockIndex b0 = blockOfVoxel(boxes[c].lo), b1 = blockOfVoxel(boxes[c].hi);
    for (int z = b0.z(); z <= b1.z(); ++z)
      for (int y = b0.y(); y <= b1.y(); ++y)
        for (int x = b0.x(); x <= b1.x(); ++x) {
          links.block_clusters[BlockIndex(x, y, z)].push_back(static_cast<std::int32_t>(c));
        }
  }
  return links;
}

}  // namespace strata::plan
