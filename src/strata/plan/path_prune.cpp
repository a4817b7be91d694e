// Line-of-sight pruning (contract in path_prune.h).
#include "strata/plan/internal/path_prune.h"

namespace strata::plan {

std::vector<Eigen::Vector3f> prunePath(const std::vector<Eigen::Vector3f>& path_W,
                                       CollisionChecker& checker, float radius_m,
                                       UnknownPolicy unknown) {
  if (path_W.size() <= 2) return path_W;
  std::vector<Eigen::Vector3f> out{path_W.front()};
  std::size_t anchor = 0;
  while (anchor + 1 < path_W.size()) {
    // Walk forward while the next point is still visible from the anchor. NOTE: a greedy walk,
    // not a search for the farthest visible point: visibility along a grid path is nearly
    // monotone and the walk costs one segment test per point.
    std::size_t reach = anchor + 1;
    while (reach + 1 < path_W.size() &&
           checker.segmentFree(path_W[anchor], path_W[reach + 1], radius_m, unknown)) {
      ++reach;
    }
    out.push_back(path_W[reach]);
    anchor = reach;
  }
  return out;
}

std::vector<Eigen::Vector3f> relaxPath(std::vector<Eigen::Vector3f> path_W,
                                       CollisionChecker& checker, float radius_m,
                                       UnknownPolicy unknown, int sweeps) {
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    bool moved = false;
    for (std::size_t i = 1; i + 1 < path_W.size(); ++i) {
      const Eigen::Vector3f mid = 0.5f * (path_W[i - 1] + path_W[i + 1]);
      for (float t : {0.5f, 0.25f, 0.125f}) {
        const Eigen::Vector3f p = path_W[i] + t * (mid - path_W[i]);
        if (checker.segmentFree(path_W[i - 1], p, radius_m, unknown) &&
            checker.segmentFree(p, path_W[i + 1], radius_m, unknown)) {
          path_W[i] = p;
          moved = true;
          break;
        }
      }
    }
    if (!moved) break;
  }
  return path_W;
}

}  // namespace strata::plan
