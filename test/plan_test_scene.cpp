#include "plan_test_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "strata/esdf/esdf.h"

namespace strata::test {

float boxDistance(const Eigen::Vector3f& p, const Box& box) {
  const Eigen::Vector3f centre = 0.5f * (box.lo + box.hi);
  const Eigen::Vector3f half = 0.5f * (box.hi - box.lo);
  const Eigen::Vector3f q = (p - centre).cwiseAbs() - half;
  return q.cwiseMax(0.0f).norm() + std::min(q.maxCoeff(), 0.0f);
}

float sceneDistance(const Eigen::Vector3f& p, const std::vector<Box>& boxes,
                    const std::vector<Ball>& balls) {
  float d = std::numeric_limits<float>::infinity();
  for (const Box& b : boxes) d = std::min(d, boxDistance(p, b));
  for (const Ball& b : balls) d = std::min(d, (p - b.centre).norm() - b.radius_m);
  return d;
}

float segmentDistance(const Sdf& sdf, const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / 0.001f)));
  float d = std::numeric_limits<float>::infinity();
  for (int k = 0; k <= n; ++k) d = std::min(d, sdf(a + (b - a) * (static_cast<float>(k) / n)));
  return d;
}

AnalyticMap makeAnalyticMap(const Sdf& sdf, const Eigen::Vector3i& block_lo,
                            const Eigen::Vector3i& block_hi, float voxel_size_m,
                            float max_distance_m) {
  MapConfig config;
  config.voxel_size_m = voxel_size_m;
  AnalyticMap out{TsdfMap(config), EsdfMap{}};
  const float truncation_m = config.truncationDistance();
  for (int bz = block_lo.z(); bz <= block_hi.z(); ++bz) {
    for (int by = block_lo.y(); by <= block_hi.y(); ++by) {
      for (int bx = block_lo.x(); bx <= block_hi.x(); ++bx) {
        const BlockIndex b(bx, by, bz);
        TsdfBlock& block = out.tsdf.allocateBlock(b);
        for (int i = 0; i < kVoxelsPerBlock; ++i) {
          const GlobalVoxelIndex v =
              b * kBlockEdge + GlobalVoxelIndex(i % kBlockEdge, (i / kBlockEdge) % kBlockEdge,
                                                i / (kBlockEdge * kBlockEdge));
          block[i].tsdf_m =
              std::clamp(sdf(voxelCenter(v, voxel_size_m)), -truncation_m, truncation_m);
          block[i].weight = 1.0f;
        }
      }
    }
  }
  EsdfConfig esdf_config;
  esdf_config.max_distance_m = max_distance_m;
  out.esdf = computeEsdfReference(out.tsdf, esdf_config);
  return out;
}

const RoomScene& roomScene(bool door_open) {
  auto build = [](bool open) {
    RoomScene s;
    using S = RoomScene;
    const float far = 10.0f;
    if (open) {
      s.walls.push_back({{-S::kWallHalfX, -far, -far}, {S::kWallHalfX, S::kDoorLoY, far}});
      s.walls.push_back({{-S::kWallHalfX, S::kDoorHiY, -far}, {S::kWallHalfX, far, far}});
    } else {
      s.walls.push_back({{-S::kWallHalfX, -far, -far}, {S::kWallHalfX, far, far}});
    }
    const std::vector<Box> walls = s.walls;
    s.map =
        makeAnalyticMap([walls](const Eigen::Vector3f& p) { return sceneDistance(p, walls, {}); },
                        {-4, -3, 0}, {3, 2, 1}, S::kVoxelSizeM, 1.5f);
    return s;
  };
  static const RoomScene open = build(true);
  static const RoomScene closed = build(false);
  return door_open ? open : closed;
}

}  // namespace strata::test
