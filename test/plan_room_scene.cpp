#include "plan_room_scene.h"

#include <algorithm>
#include <cmath>

#include "change_test_scene.h"
#include "strata/esdf/esdf.h"

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
  // Observed wherever in front of or within the band; deep inside walls never.
  return makeSdfMap([this](const Eigen::Vector3d& p) { return signedDistance(p); }, kLo, kHi,
                    kVoxelM, [](const Eigen::Vector3d&) { return true; });
}

EsdfMap PlanRoom::esdf() const {
  EsdfConfig config;
  config.max_distance_m = kMaxDistanceM;
  return computeEsdfReference(tsdf(), config);
}

}  // namespace strata::test
