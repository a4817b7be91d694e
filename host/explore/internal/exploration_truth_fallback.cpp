// TEMPORARY: see exploration_truth_fallback.h.
#include "explore/internal/exploration_truth_fallback.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace strata::eval {

ReachableSpace computeReachableSpace(const sim::WorldScene& scene,
                                     const Eigen::AlignedBox3f& bounds_W,
                                     const Eigen::Vector3f& start_W, float voxel_size_m) {
  if (!(voxel_size_m > 0.0f)) throw InputError("reachable space: voxel size must be > 0");
  if (!start_W.allFinite() || !bounds_W.contains(start_W)) {
    throw InputError("reachable space: the start lies outside the world's bounds");
  }
  if (scene.occupied(start_W)) throw InputError("reachable space: the start is inside a solid");
  const Eigen::Vector3i lo = (bounds_W.min() / voxel_size_m).array().ceil().cast<int>();
  const Eigen::Vector3i hi =
      Eigen::Vector3i((bounds_W.max() / voxel_size_m).array().floor().cast<int>()) -
      Eigen::Vector3i::Ones();
  const Eigen::Vector3i size = (hi - lo + Eigen::Vector3i::Ones()).cwiseMax(0);
  // 0: not visited, 1: reachable, 2: solid.
  std::vector<std::uint8_t> state(static_cast<std::size_t>(size.prod()), 0);
  auto index = [&](const Eigen::Vector3i& v) {
    const Eigen::Vector3i l = v - lo;
    return (static_cast<std::size_t>(l.z()) * size.y() + l.y()) * size.x() + l.x();
  };
  auto inside = [&](const Eigen::Vector3i& v) {
    return (v.array() >= lo.array()).all() && (v.array() <= hi.array()).all();
  };
  ReachableSpace out;
  out.voxel_size_m = voxel_size_m;
  const Eigen::Vector3i start = (start_W / voxel_size_m).array().floor().cast<int>();
  if (!inside(start))
    throw InputError("reachable space: the start lies outside the world's bounds");
  std::vector<Eigen::Vector3i> stack{start};
  state[index(start)] = 1;
  const Eigen::Vector3i steps[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                    {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  while (!stack.empty()) {
    const Eigen::Vector3i v = stack.back();
    stack.pop_back();
    out.voxels.push_back(v);
    for (const Eigen::Vector3i& s : steps) {
      const Eigen::Vector3i n = v + s;
      if (!inside(n) || state[index(n)] != 0) continue;
      const Eigen::Vector3f centre =
          (n.cast<float>() + Eigen::Vector3f::Constant(0.5f)) * voxel_size_m;
      const bool solid = scene.occupied(centre);
      state[index(n)] = solid ? 2 : 1;
      if (!solid) stack.push_back(n);
    }
  }
  return out;
}

double exploredFraction(const ReachableSpace& reachable, const TsdfMap& map, float min_weight) {
  if (reachable.voxels.empty()) return 0.0;
  const float map_voxel = map.config().voxel_size_m;
  std::size_t observed = 0;
  for (const Eigen::Vector3i& v : reachable.voxels) {
    const Eigen::Vector3f centre =
        (v.cast<float>() + Eigen::Vector3f::Constant(0.5f)) * reachable.voxel_size_m;
    const TsdfVoxel* voxel = map.findVoxel((centre / map_voxel).array().floor().cast<int>());
    if (voxel != nullptr && voxel->weight >= min_weight) ++observed;
  }
  return static_cast<double>(observed) / static_cast<double>(reachable.voxels.size());
}

float minClearanceAlong(const sim::WorldScene& scene,
                        const std::vector<Eigen::Vector3f>& positions_W) {
  float best = std::numeric_limits<float>::infinity();
  for (const Eigen::Vector3f& p : positions_W) best = std::min(best, scene.signedDistance(p));
  return best;
}

}  // namespace strata::eval
