#include "strata/repeat/taught_route.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "strata/core/error.h"
#include "strata/repeat/truth_checker.h"
#include "strata/sim/session/session_path.h"

namespace strata::repeat {

explore::RobotConfig RouteConfig::defaultRobot() {
  explore::RobotConfig robot;
  robot.max_speed_mps = 1.0f;
  robot.max_accel_mps2 = 1.0f;
  robot.max_yaw_rate_radps = 0.75f;
  robot.radius_m = 0.3f;
  return robot;
}

void RouteConfig::validate() const {
  robot.validate();
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(height_m)) throw InputError("route height must be > 0 m");
  if (!(min_length_m >= 0.0) || !std::isfinite(min_length_m)) {
    throw InputError("route min_length_m must be >= 0");
  }
  if (!positive(clearance_m)) throw InputError("route clearance must be > 0 m");
  if (!(teach_margin_m >= 0.0 && teach_margin_m < 1.0)) {
    throw InputError("route teach_margin_m must be in [0, 1) m");
  }
  if (!positive(step_s)) throw InputError("route step must be > 0 s");
  if (!positive(turn_in_place_rad) || !positive(slow_speed_mps)) {
    throw InputError("route turn_in_place_rad and slow_speed_mps must be > 0");
  }
}

double polylineLength(const std::vector<Eigen::Vector3f>& points_W) {
  double length = 0.0;
  for (std::size_t i = 1; i < points_W.size(); ++i) {
    length += (points_W[i] - points_W[i - 1]).norm();
  }
  return length;
}

std::vector<Eigen::Vector3f> routeWaypoints(const sim::World& world, const RouteConfig& config) {
  config.validate();
  sim::SessionPathConfig path;
  path.height_m = config.height_m;
  path.jitter_m = 0.0;
  path.min_clearance_m = config.clearance_m;
  std::vector<Eigen::Vector3f> there;
  for (const sim::Waypoint& w : sim::sessionWaypoints(world, 0, path)) {
    const Eigen::Vector3f p = w.position_W.cast<float>();
    if (there.empty() || (p - there.back()).norm() > 1e-3f) there.push_back(p);
  }
  if (there.size() < 2) {
    throw InputError("world '" + world.name() + "': its session path has fewer than 2 waypoints");
  }
  std::vector<Eigen::Vector3f> back(there.rbegin(), there.rend());
  std::vector<Eigen::Vector3f> route = there;
  for (bool forth = false; polylineLength(route) < config.min_length_m; forth = !forth) {
    const std::vector<Eigen::Vector3f>& leg = forth ? there : back;
    route.insert(route.end(), leg.begin() + 1, leg.end());
  }
  return route;
}

float turnTowards(float yaw_rad, float target_rad, float max_step_rad) {
  const float error = explore::wrapAngle(target_rad - yaw_rad);
  return explore::wrapAngle(yaw_rad + std::clamp(error, -max_step_rad, max_step_rad));
}

bool headingAt(const plan::Trajectory& trajectory, double t_s, float& yaw_rad) {
  const Eigen::Vector3f here = trajectory.at(t_s).p_W;
  for (double ahead_s = 0.2; t_s + ahead_s <= trajectory.duration_s + 0.2; ahead_s += 0.2) {
    const Eigen::Vector3f d = trajectory.at(t_s + ahead_s).p_W - here;
    if (d.head<2>().norm() > 0.02f) {
      yaw_rad = std::atan2(d.y(), d.x());
      return true;
    }
  }
  return false;
}

std::vector<FlightState> flyRoute(const std::vector<Eigen::Vector3f>& waypoints,
                                  const sim::WorldScene& scene, const RouteConfig& config) {
  config.validate();
  TruthChecker checker(scene);
  plan::TrajectoryLimits limits;
  limits.v_max_mps = config.teach_speed_share * config.robot.max_speed_mps;
  limits.a_max_mps2 = config.teach_speed_share * config.robot.max_accel_mps2;
  const plan::Trajectory trajectory = plan::makeTrajectory(
      waypoints, limits, checker, config.robot.radius_m + static_cast<float>(config.teach_margin_m),
      UnknownPolicy::kFree);
  if (trajectory.samples.size() < 2 || trajectory.duration_s <= 0.0) {
    throw InputError("the route has fewer than two distinct waypoints");
  }
  const float max_turn = static_cast<float>(config.robot.max_yaw_rate_radps * config.step_s);
  float yaw = 0.0f;
  headingAt(trajectory, 0.0, yaw);
  std::vector<FlightState> flight;
  double tau = 0.0, t = 0.0;
  // Waiting to turn can never take longer than a half turn per stop.
  const std::size_t limit =
      static_cast<std::size_t>(10.0 * (trajectory.duration_s + 60.0) / config.step_s);
  while (flight.size() < limit) {
    const plan::TrajectorySample s = trajectory.at(tau);
    flight.push_back({t, s.p_W, yaw, s.v_W.norm()});
    if (tau >= trajectory.duration_s) break;
    float heading = yaw;
    const bool ahead = headingAt(trajectory, tau, heading);
    const float error = std::abs(explore::wrapAngle(heading - yaw));
    const bool turn_first =
        ahead && error > config.turn_in_place_rad && s.v_W.norm() < config.slow_speed_mps;
    if (!turn_first) tau = std::min(trajectory.duration_s, tau + config.step_s);
    yaw = turnTowards(yaw, heading, max_turn);
    t += config.step_s;
  }
  return flight;
}

}  // namespace strata::repeat
