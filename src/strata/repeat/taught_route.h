#pragma once
// The route a teach flies through a simulated world, and the flight along it.
// Route: the waypoints of session 0's camera path (sim/session/session_path.h: a loop in each
// room, rooms visited over the door graph, legs planned on a free-space grid with a clearance),
// without jitter, at the flight height; flown forth and back again (the way back is the way
// there reversed, so it is as free) until the route is at least min_length_m long.
// Flight: plan::makeTrajectory over the waypoints against the world's exact geometry
// (truth_checker.h) gives the position and speed (limits of the robot); the camera looks along
// the motion, its yaw turned at most max_yaw_rate; where the heading ahead differs from the yaw
// by more than turn_in_place_rad while the robot is slow (a stop at a sharp corner or where the
// route turns back), the robot waits and turns in place, as explore's PathFollower does at a
// waypoint.
// Frames: world (z up), metres, seconds; yaw about +z from +x. Thread safety: functions only.
#include <Eigen/Core>
#include <vector>

#include "strata/explore/robot_model.h"
#include "strata/plan/flight_trajectory.h"
#include "strata/sim/world/world.h"

namespace strata::repeat {

struct RouteConfig {
  /// Flight height above the floor (metres).
  double height_m = 1.2;
  /// The route is flown forth and back until it is at least this long (metres).
  double min_length_m = 50.0;
  /// The session path's legs keep this far from every surface (metres); more than 0.45 closes
  /// the office's 0.9 m doors.
  double clearance_m = 0.4;
  /// Speed, acceleration and yaw rate of the robot; its radius for the trajectory's check.
  explore::RobotConfig robot = defaultRobot();
  /// The teach's trajectory keeps this much more than the robot's radius from every surface
  /// where the route allows (corners are rounded only as far as it allows): a repeat some
  /// centimetres off the taught path then still clears the robot's radius.
  double teach_margin_m = 0.1;
  /// The teach flies at this share of the robot's speed and acceleration limits (0.75 m/s).
  double teach_speed_share = 0.75;
  /// Time step of the flight's states (seconds).
  double step_s = 0.05;
  /// A slow robot (below slow_speed_mps) whose heading ahead is off by more than this turns in
  /// place first (radians).
  double turn_in_place_rad = 0.5;
  double slow_speed_mps = 0.15;

  static explore::RobotConfig defaultRobot();
  /// InputError naming the bad field.
  void validate() const;
};

/// One state of a flight.
struct FlightState {
  double t_s = 0.0;
  Eigen::Vector3f p_W = Eigen::Vector3f::Zero();
  float yaw_rad = 0.0f;
  float speed_mps = 0.0f;
};

/// The route's waypoints (world frame). InputError for a world without rooms.
std::vector<Eigen::Vector3f> routeWaypoints(const sim::World& world, const RouteConfig& config);

/// The flight along `waypoints` in `scene`, one state every config.step_s from rest to rest.
/// InputError for fewer than two distinct waypoints.
std::vector<FlightState> flyRoute(const std::vector<Eigen::Vector3f>& waypoints,
                                  const sim::WorldScene& scene, const RouteConfig& config);

/// Heading (yaw, radians) of the polyline's direction of travel at `t_s` along `trajectory`:
/// the direction to where it is a moment later, looking further ahead through a stop; false
/// (yaw_rad untouched) at the end.
bool headingAt(const plan::Trajectory& trajectory, double t_s, float& yaw_rad);

/// Turns `yaw_rad` towards `target_rad` by at most max_step_rad (wrapped).
float turnTowards(float yaw_rad, float target_rad, float max_step_rad);

/// Polyline length (metres).
double polylineLength(const std::vector<Eigen::Vector3f>& points_W);

}  // namespace strata::repeat
