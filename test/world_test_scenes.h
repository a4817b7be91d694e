#pragma once
// The worlds the world tests share: the shipped world names and a one-box room with its exact
// signed distance.
#include <Eigen/Core>
#include <algorithm>
#include <string>

namespace strata::sim::test {

inline constexpr const char* kShippedWorlds[] = {"room", "office", "warehouse", "deadend"};
/// Shipped worlds for mapping over several sessions (deadend is one session, for exploration).
inline constexpr const char* kMultiSessionWorlds[] = {"room", "office", "warehouse"};

/// One room 4 x 3 x 2.5 m with one box (0.6 x 0.4 x 0.5) at (2, 1.5), yaw `yaw` degrees.
inline std::string boxRoomYaml(double yaw_deg) {
  return "name: box_room\nsessions: 1\nwall_thickness: 0.1\n"
         "rooms:\n  - {min: [0, 0], max: [4, 3], height: 2.5, floor: {albedo: [10, 20, 30]}}\n"
         "objects:\n  - {name: crate, type: box, size: [0.6, 0.4, 0.5], at: [2, 1.5], yaw: " +
         std::to_string(yaw_deg) + ", albedo: [200, 60, 40], reflectivity: 0.5}\n";
}

/// Signed distance to the box room above, with the box at yaw 0: min over floor, ceiling, walls
/// (interior faces) and the box. Exact outside every solid and inside the box.
inline double analyticBoxRoomSdf(const Eigen::Vector3d& p) {
  const double room = std::min({p.z(), 2.5 - p.z(), p.x(), 4.0 - p.x(), p.y(), 3.0 - p.y()});
  const Eigen::Vector3d centre(2.0, 1.5, 0.25), half(0.3, 0.2, 0.25);
  const Eigen::Vector3d q = (p - centre).cwiseAbs() - half;
  const double box = q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
  return std::min(room, box);
}

}  // namespace strata::sim::test
