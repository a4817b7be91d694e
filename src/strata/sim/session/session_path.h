#pragma once
// The camera path of one mapping session through a world: a loop inside each room, rooms visited
// in a walk over the door graph, legs planned on a free-space grid (through doors, around shelves
// and pillars, never through walls), varied per session.
#include <cstdint>
#include <vector>

#include "strata/sim/sensors/camera_path.h"
#include "strata/sim/world/world.h"

namespace strata::sim {

struct SessionPathConfig {
  /// Camera height above the floor (hand-held).
  double height_m = 1.4;
  /// Loops keep this far from the room's walls.
  double wall_margin_m = 0.8;
  /// Waypoints per room loop.
  int loop_waypoints = 6;
  /// Random displacement of each waypoint per session (different visits, different paths).
  double jitter_m = 0.15;
  /// The camera keeps at least this distance from every surface (paths are planned on a grid).
  double min_clearance_m = 0.4;
};

/// Waypoints of `session`'s path. Throws InputError for a world without rooms.
std::vector<Waypoint> sessionWaypoints(const World& world, int session,
                                       const SessionPathConfig& config = {});

/// The session's trajectory through those waypoints, refined where the spline would pass closer
/// than half the clearance to a surface of `scene`.
Trajectory sessionTrajectory(const World& world, int session, const WorldScene& scene,
                             const SessionPathConfig& path_config,
                             const TrajectoryConfig& trajectory_config, std::uint64_t seed);

}  // namespace strata::sim
