#include "plan_room_scene.h"

#include <algorithm>
#include <cmath>

#include "esdf/esdf.h"

namespace strata::test {
namespace {

double boxDistance(const Eigen::Vector3d& p, const Eigen::AlignedBox3d& box) {
  const Eigen::Vector3d q = (p - box.center()).cwiseAbs() - 0.5 * box.sizes();
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

const Eigen::AlignedBox3d kInterior(Eigen::Vector3d(0.0, 0.0, 0.0), Eigen::Vector3d(4.0, 3.0, 1.2));
// The scene's blocks cover this (a wall thickness around the interior).
const Eigen::Vector3d kLo(-0.3, -0.3, -0.3), kHi(4.3, 3.3, 1.5);

}  // namespace

double PlanRoom::signedDistance(const Eigen::Vector3d& p) const {
  double d = -boxDistance(p, kInterior);  // positive inside the room
  const Eigen::AlignedBox3d below(Eigen::Vector3d(kWallX0, -1.0, -1.0),
                                  Eigen::Vector3d(kWallX1, door_open ? kDoorY0 : 4.0, 2.0));
  d = std::min(d, boxDistance(p, below));
  if (door_open) {
    const Eigen::AlignedBox3d above(Eigen::Vector3d(kWallX0, kDoorY1, -1.0),
                                    Eigen::Vector3d(kWallX1, 4.0, 2.0));
    d = std::min(d, boxDistance(p, above));
  }
  if (!extra.isEmpty()) d = std::min(d, boxDistance(p, extra));
  return d;
}

TsdfMap PlanRoom::tsdf() const {
  MapConfig config;
  config.voxel_size_m = kVoxelM;
  TsdfMap map(config);
  const double trunc = config.truncationDistance();
  const float block_m = config.blockSize();
  const BlockIndex b0 = (kLo.cast<float>() / block_m).array().floor().cast<int>();
  const BlockIndex b1 = (kHi.cast<float>() / block_m).array().floor().cast<int>();
  for (int bz = b0.z(); bz <= b1.z(); ++bz) {
    for (int by = b0.y(); by <= b1.y(); ++by) {
      for (int bx = b0.x(); bx <= b1.x(); ++bx) {
        const BlockIndex b(bx, by, bz);
        TsdfBlock& block = map.allocateBlock(b);
        for (int i = 0; i < kVoxelsPerBlock; ++i) {
          const Eigen::Vector3i local(i % 8, i / 8 % 8, i / 64);
          const double d =
              signedDistance(voxelCenter(b * kBlockEdge + local, kVoxelM).cast<double>());
          block[i].tsdf_m = static_cast<float>(std::clamp(d, -trunc, trunc));
          block[i].weight = d > -trunc ? 20.0f : 0.0f;  // deep inside walls: never observed
        }
      }
    }
  }
  return map;
}

EsdfMap PlanRoom::esdf() const {
  EsdfConfig config;
  config.max_distance_m = kMaxDistanceM;
  return computeEsdfReference(tsdf(), config);
}

}  // namespace strata::test
