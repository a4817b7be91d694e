#include "esdf_sphere_scene.h"

#include <cmath>
#include <limits>

#include "strata/map/tsdf_map.h"

namespace strata::test {
namespace {

using Scene = SphereEsdfScene;

bool isAllocated(const BlockIndex& b) { return b != Scene::kMissingBlock; }

bool isObserved(const GlobalVoxelIndex& v) {
  return v.x() < Scene::kUnknownSlabX0 || v.x() >= Scene::kUnknownSlabX1;
}

template <typename Visit>
void forEachVoxel(Visit visit) {
  for (int bz = Scene::kBlockMin; bz <= Scene::kBlockMax; ++bz) {
    for (int by = Scene::kBlockMin; by <= Scene::kBlockMax; ++by) {
      for (int bx = Scene::kBlockMin; bx <= Scene::kBlockMax; ++bx) {
        const BlockIndex b(bx, by, bz);
        if (!isAllocated(b)) continue;
        for (int i = 0; i < kVoxelsPerBlock; ++i) {
          const Eigen::Vector3i local(i % kBlockEdge, (i / kBlockEdge) % kBlockEdge,
                                      i / (kBlockEdge * kBlockEdge));
          visit(b, i, GlobalVoxelIndex(b * kBlockEdge + local));
        }
      }
    }
  }
}

/// The ESDF voxel of v by the layer's contract: exact nearest site, sign inside, capped.
EsdfVoxel exactVoxel(const Scene& scene, const GlobalVoxelIndex& v,
                     const std::vector<GlobalVoxelIndex>& sites) {
  EsdfVoxel out;
  if (!isObserved(v)) return out;  // unknown: no flags
  int best_d2 = std::numeric_limits<int>::max();
  Eigen::Vector3i best_offset = Eigen::Vector3i::Zero();
  for (const GlobalVoxelIndex& s : sites) {
    const int d2 = (s - v).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best_offset = s - v;
    }
  }
  const float reach = Scene::kMaxDistanceM / Scene::kVoxelSizeM;
  out.site_and_flags = kEsdfObservedBit;
  out.distance_m = Scene::kMaxDistanceM;
  if (static_cast<float>(best_d2) <= reach * reach) {
    out.site_and_flags |= kEsdfHasSiteBit | packSiteOffset(best_offset);
    out.distance_m = std::sqrt(static_cast<float>(best_d2)) * Scene::kVoxelSizeM;
  }
  if (scene.surfaceDistance(voxelCenter(v, Scene::kVoxelSizeM)) < 0.0f) {
    out.distance_m = -out.distance_m;
  }
  return out;
}

}  // namespace

float SphereEsdfScene::nearestSiteDistance(const Eigen::Vector3f& p_W) const {
  float best = std::numeric_limits<float>::infinity();
  for (const Eigen::Vector3f& s : sites_W) best = std::fmin(best, (s - p_W).norm());
  return best;
}

const SphereEsdfScene& sphereEsdfScene() {
  static const SphereEsdfScene scene = [] {
    SphereEsdfScene s;
    s.map.voxel_size_m = Scene::kVoxelSizeM;
    s.map.config.max_distance_m = Scene::kMaxDistanceM;
    std::vector<GlobalVoxelIndex> sites;
    forEachVoxel([&](const BlockIndex&, int, const GlobalVoxelIndex& v) {
      const Eigen::Vector3f c = voxelCenter(v, Scene::kVoxelSizeM);
      if (isObserved(v) && std::fabs(s.surfaceDistance(c)) <= 0.5f * Scene::kVoxelSizeM) {
        sites.push_back(v);
        s.sites_W.push_back(c);
      }
    });
    forEachVoxel([&](const BlockIndex& b, int i, const GlobalVoxelIndex& v) {
      s.map.blocks[b][i] = exactVoxel(s, v, sites);
    });
    return s;
  }();
  return scene;
}

DeviceSphereEsdf uploadSphereEsdf(vk::Context& context, const SphereEsdfScene& scene) {
  MapConfig config;
  config.voxel_size_m = scene.map.voxel_size_m;
  TsdfMap tsdf(config);
  for (const auto& [b, block] : scene.map.blocks) tsdf.allocateBlock(b);
  DeviceSphereEsdf out;
  out.tsdf = std::make_unique<DeviceTsdfMap>(context, config);
  out.tsdf->upload(tsdf);
  // The ESDF pool follows the TSDF slots.
  std::vector<EsdfBlock> pool(out.tsdf->blockCount());
  for (const auto& [b, slot] : out.tsdf->blockSlots()) pool.at(slot) = scene.map.blocks.at(b);
  out.esdf_pool = vk::Buffer::create(context, pool.size() * sizeof(EsdfBlock),
                                     vk::MemoryUsage::kDeviceLocal, "test ESDF pool");
  vk::upload(context, out.esdf_pool, pool.data(), pool.size() * sizeof(EsdfBlock));
  return out;
}

}  // namespace strata::test
