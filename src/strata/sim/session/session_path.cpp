#include "strata/sim/session/session_path.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>

#include "strata/core/error.h"
#include "strata/sim/rng.h"
#include "strata/sim/session/internal/free_space_grid.h"
#include "strata/core/math_constants.h"

namespace strata::sim {
namespace {

constexpr double kLookAtHeight_m = 0.6;  // objects stand on the floor: look slightly down

Eigen::Vector2d centre(const RoomSpec& room) { return 0.5 * (room.min_m + room.max_m); }

/// Rooms whose walls hold the door point (interior grown by the wall thickness).
std::vector<int> roomsAtDoor(const WorldSpec& spec, const DoorSpec& door) {
  std::vector<int> rooms;
  const double grow = spec.wall_thickness_m + 0.05;
  for (int r = 0; r < static_cast<int>(spec.rooms.size()); ++r) {
    const RoomSpec& room = spec.rooms[r];
    if ((door.at_m.array() >= room.min_m.array() - grow).all() &&
        (door.at_m.array() <= room.max_m.array() + grow).all()) {
      rooms.push_back(r);
    }
  }
  return rooms;
}

struct WalkStep {
  int room;
  int via_door;  // -1 for the start
  bool first_visit;
};

/// Depth-first walk over the door graph from room 0, returning to a room after each child.
std::vector<WalkStep> roomWalk(const WorldSpec& spec) {
  std::vector<WalkStep> walk;
  std::vector<bool> visited(spec.rooms.size(), false);
  std::function<void(int, int)> visit = [&](int room, int via_door) {
    visited[room] = true;
    walk.push_back({room, via_door, true});
    for (int d = 0; d < static_cast<int>(spec.doors.size()); ++d) {
      const std::vector<int> rooms = roomsAtDoor(spec, spec.doors[d]);
      if (std::find(rooms.begin(), rooms.end(), room) == rooms.end()) continue;
      for (int next : rooms) {
        if (next == room || visited[next]) continue;
        visit(next, d);
        walk.push_back({room, d, false});  // back through the same door
      }
    }
  };
  visit(0, -1);
  return walk;
}

/// Loop targets inside a room: an inset ellipse, jittered per session.
std::vector<Eigen::Vector2d> roomLoop(const RoomSpec& room, const SessionPathConfig& config,
                                      Rng& rng) {
  const Eigen::Vector2d c = centre(room);
  const Eigen::Vector2d radius =
      (((room.max_m - room.min_m) * 0.5).array() - config.wall_margin_m).matrix().cwiseMax(0.2);
  const double phase = rng.uniform() * 2.0 * kPi;
  std::vector<Eigen::Vector2d> loop;
  for (int k = 0; k <= config.loop_waypoints; ++k) {  // closed: back to the first point
    const double a = phase + 2.0 * kPi * k / config.loop_waypoints;
    loop.push_back(c + Eigen::Vector2d(radius.x() * std::cos(a), radius.y() * std::sin(a)) +
                   config.jitter_m * Eigen::Vector2d(rng.normal(), rng.normal()));
  }
  return loop;
}

/// Where the camera looks from p: the centre of the room it is in (objects stand around it), or
/// ahead along the path when that centre is too close to look at.
Eigen::Vector3d lookAtFrom(const WorldSpec& spec, const Eigen::Vector2d& p,
                           const Eigen::Vector2d& ahead) {
  for (const RoomSpec& room : spec.rooms) {
    if ((p.array() < room.min_m.array()).any() || (p.array() > room.max_m.array()).any()) continue;
    const Eigen::Vector2d c = centre(room);
    if ((c - p).norm() > 0.8) return Eigen::Vector3d(c.x(), c.y(), kLookAtHeight_m);
  }
  const Eigen::Vector2d direction =
      (ahead - p).norm() > 1e-6 ? (ahead - p).normalized() : Eigen::Vector2d::UnitX();
  const Eigen::Vector2d target = p + 2.0 * direction;
  return Eigen::Vector3d(target.x(), target.y(), kLookAtHeight_m + 0.4);
}

/// Consecutive waypoints' views turn by at most kMaxViewTurn_rad. Where the chosen target
/// jumps (the room centre comes too close and the view switches to ahead, or a door leads into
/// a room whose centre lies behind), the two targets sat on opposite sides of the path, and the
/// look-at spline between them passed through the camera: the view flipped by up to 180 degrees
/// in a few milliseconds (tens of thousands of degrees per second in the office's sessions),
/// which no camera does. A clamped target keeps its height and the previous target's distance
/// (from above): a target that also jumped in distance (5 m behind to 11 m ahead at the dead-end
/// world's junction) made the interpolated view swing faster than the clamp allows.
void limitViewTurn(const Eigen::Vector2d& p, Eigen::Vector3d* target,
                   std::optional<Eigen::Vector2d>* previous_offset) {
  constexpr double kMaxViewTurn_rad = 45.0 * M_PI / 180.0;  // per 0.5 m of path
  Eigen::Vector2d offset = target->head<2>() - p;
  const double distance = offset.norm();
  if (distance < 1e-6) return;
  if (*previous_offset && (*previous_offset)->norm() > 1e-6) {
    const Eigen::Vector2d v0 = (*previous_offset)->normalized();
    const Eigen::Vector2d view = offset / distance;
    const double turn = std::atan2(v0.x() * view.y() - v0.y() * view.x(), v0.dot(view));
    if (std::abs(turn) > kMaxViewTurn_rad) {
      const double a = std::copysign(kMaxViewTurn_rad, turn);
      const Eigen::Vector2d clamped(std::cos(a) * v0.x() - std::sin(a) * v0.y(),
                                    std::sin(a) * v0.x() + std::cos(a) * v0.y());
      offset = (*previous_offset)->norm() * clamped;
      target->head<2>() = p + offset;
    }
  }
  *previous_offset = offset;
}

}  // namespace

std::vector<Waypoint> sessionWaypoints(const World& world, int session,
                                       const SessionPathConfig& config) {
  const WorldSpec& spec = world.spec();
  if (spec.rooms.empty()) throw InputError("world '" + world.name() + "' has no rooms to walk");
  const std::unique_ptr<WorldScene> scene = world.buildScene(session);
  const Eigen::AlignedBox3d bounds3 = world.bounds();
  const Eigen::AlignedBox2d bounds(bounds3.min().head<2>(), bounds3.max().head<2>());
  const FreeSpaceGrid grid(*scene, bounds, config.height_m, config.min_clearance_m);
  Rng rng(hashCombine(world.seed(), 0x5e55104ull + static_cast<std::uint64_t>(session)));

  // Targets: a loop in each room, rooms in a walk over the door graph.
  std::vector<Eigen::Vector2d> targets;
  for (const WalkStep& step : roomWalk(spec)) {
    if (!step.first_visit) continue;  // the planner finds the way back through the doors
    for (const Eigen::Vector2d& t : roomLoop(spec.rooms[step.room], config, rng)) {
      targets.push_back(t);
    }
  }
  // Planned legs between consecutive targets, one waypoint every kWaypointSpacing_cells.
  constexpr std::size_t kWaypointSpacing_cells = 5;  // 0.5 m: dense enough that the spline follows
  std::vector<Eigen::Vector2d> points;
  std::size_t from = 0;
  for (std::size_t i = 1; i < targets.size(); ++i) {
    const std::vector<Eigen::Vector2d> leg = grid.path(targets[from], targets[i]);
    if (leg.empty()) continue;  // unreachable target (e.g. a room behind too narrow a door): skip
    for (std::size_t k = 0; k < leg.size(); k += kWaypointSpacing_cells) {
      if (points.empty() || (points.back() - leg[k]).norm() > 0.2) points.push_back(leg[k]);
    }
    from = i;
  }
  if (points.size() < 2) {
    throw InputError("world '" + world.name() + "': no free space for a camera path at " +
                     std::to_string(config.height_m) + " m height");
  }
  std::vector<Waypoint> waypoints;
  std::optional<Eigen::Vector2d> previous_offset;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d& p = points[i];
    const Eigen::Vector2d& ahead = points[std::min(i + 1, points.size() - 1)];
    Eigen::Vector3d target = lookAtFrom(spec, p, ahead);
    limitViewTurn(p, &target, &previous_offset);
    waypoints.push_back({Eigen::Vector3d(p.x(), p.y(), config.height_m), target});
  }
  return waypoints;
}

}  // namespace strata::sim

namespace strata::sim {

Trajectory sessionTrajectory(const World& world, int session, const WorldScene& scene,
                             const SessionPathConfig& path_config,
                             const TrajectoryConfig& trajectory_config, std::uint64_t seed) {
  // An interpolating spline overshoots between waypoints at sharp turns; where a sampled pose
  // comes closer to a surface than half the clearance, the waypoints around it get midpoints
  // (consecutive waypoints are joined by free straight lines), which pulls the curve back.
  std::vector<Waypoint> waypoints = sessionWaypoints(world, session, path_config);
  const float min_distance_m = static_cast<float>(0.5 * path_config.min_clearance_m);
  for (int round = 0;; ++round) {
    Trajectory trajectory(waypoints, trajectory_config, seed);
    const double segment_s = trajectory.duration_s() / static_cast<double>(waypoints.size() - 1);
    std::vector<bool> refine(waypoints.size(), false);
    bool clear = true;
    for (double t : trajectory.sampleTimes(20.0)) {
      const Eigen::Vector3f p = trajectory.pose(t).translation().cast<float>();
      if (scene.signedDistance(p) >= min_distance_m) continue;
      clear = false;
      const std::size_t k = std::min(static_cast<std::size_t>(t / segment_s), waypoints.size() - 2);
      refine[k] = true;
      if (k > 0) refine[k - 1] = true;
      if (k + 2 < waypoints.size()) refine[k + 1] = true;
    }
    if (clear || round == 6) return trajectory;
    std::vector<Waypoint> refined;
    for (std::size_t k = 0; k < waypoints.size(); ++k) {
      refined.push_back(waypoints[k]);
      if (k + 1 < waypoints.size() && refine[k]) {
        refined.push_back({0.5 * (waypoints[k].position_W + waypoints[k + 1].position_W),
                           waypoints[k].look_at_W});
      }
    }
    waypoints = std::move(refined);
  }
}

}  // namespace strata::sim
