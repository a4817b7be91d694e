#include "plan_update.h"

#include <algorithm>
#include <chrono>

#include "strata/esdf/esdf.h"

namespace strata::bench {
namespace {

double boxDistance(const Eigen::Vector3d& p, const Eigen::AlignedBox3d& box) {
  const Eigen::Vector3d q = (p - box.center()).cwiseAbs() - 0.5 * box.sizes();
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

/// The map with the box added: every voxel takes the nearer of its surface and the box's.
TsdfMap withObstacle(const TsdfMap& tsdf, const Eigen::AlignedBox3d& box) {
  TsdfMap out = tsdf;
  const float voxel_m = tsdf.config().voxel_size_m;
  const float trunc_m = tsdf.config().truncationDistance();
  for (const auto& [b, block] : tsdf.blocks()) {
    TsdfBlock& edit = *out.findBlock(b);
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      const Eigen::Vector3i local(i % kBlockEdge, i / kBlockEdge % kBlockEdge,
                                  i / (kBlockEdge * kBlockEdge));
      const auto d = static_cast<float>(
          boxDistance(voxelCenter(b * kBlockEdge + local, voxel_m).cast<double>(), box));
      if (d >= trunc_m || (edit[i].weight > 0.0f && d >= edit[i].tsdf_m)) continue;
      edit[i].tsdf_m = std::max(d, -trunc_m);
      edit[i].weight = d > -trunc_m ? 20.0f : 0.0f;
    }
  }
  return out;
}

std::vector<BlockIndex> changedBlocks(const EsdfMap& before, const EsdfMap& after) {
  std::vector<BlockIndex> out;
  for (const auto& [b, block] : after.blocks) {
    const auto it = before.blocks.find(b);
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      if (it == before.blocks.end() || it->second[i].distance_m != block[i].distance_m ||
          it->second[i].site_and_flags != block[i].site_and_flags) {
        out.push_back(b);
        break;
      }
    }
  }
  return out;
}

}  // namespace

Json measureTopoUpdate(const WorldMap& map, const Eigen::AlignedBox3d& obstacle,
                       const plan::TopoOptions& options, bool* ok) {
  plan::TopoMap topo(map.esdf, options);
  const EsdfMap changed_esdf =
      computeEsdfReference(withObstacle(map.tsdf, obstacle), map.esdf.config);
  const std::vector<BlockIndex> changed = changedBlocks(map.esdf, changed_esdf);
  topo.update(changed_esdf, changed);
  const plan::TopoMap full(changed_esdf, options);
  std::int32_t updated_components = 0, full_components = 0;
  topo.components(&updated_components);
  full.components(&full_components);
  *ok = !topo.stats().last_update_full && updated_components == full_components &&
        topo.stats().traversable_voxels == full.stats().traversable_voxels;
  return Json::object()
      .set("obstacle_min_m",
           Json::numbers({obstacle.min().x(), obstacle.min().y(), obstacle.min().z()}))
      .set("obstacle_max_m",
           Json::numbers({obstacle.max().x(), obstacle.max().y(), obstacle.max().z()}))
      .set("changed_blocks", changed.size())
      .set("blocks", map.esdf.blocks.size())
      .set("update_ms", topo.stats().update_ms)
      .set("full_rebuild_ms", full.stats().build_ms)
      .set("voxels_retested", topo.stats().voxels_retested)
      .set("grid_cells", topo.stats().grid_cells)
      .set("clusters_dropped", topo.stats().clusters_dropped)
      .set("clusters_grown", topo.stats().clusters_grown)
      .set("clusters_after_update", topo.clusters().size())
      .set("clusters_after_rebuild", full.clusters().size())
      .set("traversable_voxels_update", topo.stats().traversable_voxels)
      .set("traversable_voxels_rebuild", full.stats().traversable_voxels)
      .set("components_update", updated_components)
      .set("components_rebuild", full_components)
      .set("agrees_with_rebuild", *ok);
}

}  // namespace strata::bench
