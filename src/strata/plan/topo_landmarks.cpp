// Landmark distances on the portal graph (contract in topo_landmarks.h).
#include "strata/plan/topo_landmarks.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <queue>

#include "strata/plan/topo_map.h"

namespace strata::plan {

std::vector<float> portalDistances(const std::vector<TopoPortal>& portals,
                                   const std::vector<Eigen::Vector3f>& centres,
                                   const std::vector<std::int32_t>& offsets,
                                   const std::vector<std::int32_t>& ids, std::int32_t source) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  std::vector<float> d(portals.size(), kInf);
  using Entry = std::pair<float, std::int32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  d[static_cast<std::size_t>(source)] = 0.0f;
  open.push({0.0f, source});
  while (!open.empty()) {
    const auto [dist, p] = open.top();
    open.pop();
    if (dist > d[static_cast<std::size_t>(p)]) continue;
    const TopoPortal& portal = portals[static_cast<std::size_t>(p)];
    for (const std::int32_t c : {portal.a, portal.b}) {
      for (std::int32_t k = offsets[static_cast<std::size_t>(c)];
           k < offsets[static_cast<std::size_t>(c) + 1]; ++k) {
        const std::int32_t q = ids[static_cast<std::size_t>(k)];
        const float via =
            dist +
            (centres[static_cast<std::size_t>(q)] - centres[static_cast<std::size_t>(p)]).norm();
        if (via < d[static_cast<std::size_t>(q)]) {
          d[static_cast<std::size_t>(q)] = via;
          open.push({via, q});
        }
      }
    }
  }
  return d;
}

namespace {

/// A portal of the cluster with the most portals: inside the main component of the graph.
std::int32_t busiestPortal(const std::vector<TopoPortal>& portals,
                           const std::vector<std::int32_t>& offsets) {
  std::int32_t best = 0, best_degree = -1;
  for (std::size_t p = 0; p < portals.size(); ++p) {
    const auto c = static_cast<std::size_t>(portals[p].a);
    const std::int32_t degree = offsets[c + 1] - offsets[c];
    if (degree > best_degree) {
      best_degree = degree;
      best = static_cast<std::int32_t>(p);
    }
  }
  return best;
}

}  // namespace

TopoLandmarks::TopoLandmarks(const std::vector<TopoPortal>& portals,
                             const std::vector<Eigen::Vector3f>& centres,
                             const std::vector<std::int32_t>& offsets,
                             const std::vector<std::int32_t>& ids, int count)
    : portals_(portals.size()) {
  if (portals.empty() || count <= 0) return;
  // Farthest-first: each new landmark is the portal farthest (in the graph) from those chosen,
  // within the first landmark's component (the largest, usually: it starts at the portal of the
  // most portals' cluster); searches elsewhere fall back to the straight line.
  std::vector<float> nearest(portals.size(), -1.0f);
  std::int32_t next = busiestPortal(portals, offsets);
  for (int l = 0; l < count && l < static_cast<int>(portals.size()); ++l) {
    const std::vector<float> d = portalDistances(portals, centres, offsets, ids, next);
    distance_.insert(distance_.end(), d.begin(), d.end());
    ++count_;
    for (std::size_t p = 0; p < d.size(); ++p) {
      if (d[p] == std::numeric_limits<float>::infinity()) continue;
      nearest[p] = nearest[p] < 0.0f ? d[p] : std::min(nearest[p], d[p]);
    }
    next = static_cast<std::int32_t>(std::max_element(nearest.begin(), nearest.end()) -
                                     nearest.begin());
    if (nearest[static_cast<std::size_t>(next)] <= 0.0f) break;  // every portal is a landmark
  }
}

}  // namespace strata::plan
