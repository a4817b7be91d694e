// Leaving a dead end (contract in dead_end.h).
#include "strata/explore/dead_end.h"

#include "strata/core/error.h"

namespace strata::explore {

DeadEnd deadEndSeenFrom(const Eigen::AlignedBox2f& region_xy, const Eigen::Vector3f& start_W) {
  return {region_xy, start_W.head<2>().cwiseMax(region_xy.min()).cwiseMin(region_xy.max())};
}

DeadEndEscape analyseDeadEnd(const std::vector<double>& times_s,
                             const std::vector<Eigen::Vector3f>& positions_W,
                             const DeadEnd& dead_end, double end_time_s) {
  const Eigen::AlignedBox2f& region_xy = dead_end.region_xy;
  if (times_s.size() != positions_W.size()) {
    throw InputError("dead end: " + std::to_string(times_s.size()) + " times for " +
                     std::to_string(positions_W.size()) + " positions");
  }
  if (region_xy.isEmpty()) throw InputError("dead end: the region is empty");
  const Eigen::Vector2f& mouth = dead_end.mouth_xy;
  DeadEndEscape e;
  for (std::size_t i = 0; i < positions_W.size(); ++i) {
    const Eigen::Vector2f p = positions_W[i].head<2>();
    const bool inside = region_xy.contains(p);
    if (!e.entered) {
      if (!inside) continue;
      e.entered = true;
      e.entered_s = times_s[i];
    }
    if (!inside) {
      e.left_s = times_s[i];
      e.escape_s = times_s[i] - e.deepest_s;
      break;
    }
    const float depth_m = (p - mouth).norm();
    if (depth_m > e.deepest_m) {
      e.deepest_m = depth_m;
      e.deepest_s = times_s[i];
    }
  }
  if (e.entered) e.after_deepest_s = (e.left_s ? *e.left_s : end_time_s) - e.deepest_s;
  return e;
}

}  // namespace strata::explore
