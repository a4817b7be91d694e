#pragma once
// Smooth hand-held camera trajectories: a C4 quintic B-spline through waypoint positions, the view
// from a second spline through look-at targets, and seeded hand-held sway on top. Pose, velocity,
// acceleration and angular velocity at any time (for the IMU).
#include <Eigen/Geometry>
#include <algorithm>
#include <cstdint>
#include <vector>

#include "strata/sim/sensors/hand_jitter.h"
#include "strata/sim/sensors/quintic_spline.h"

namespace strata::sim {

struct Waypoint {
  Eigen::Vector3d position_W;
  Eigen::Vector3d look_at_W;  // the camera's optical axis points here (not straight up or down)
};

struct TrajectoryConfig {
  /// Sets the time between waypoints (uniform): mean waypoint spacing / speed. The path starts and
  /// ends at rest, so the realised mean speed is a little lower.
  double mean_speed_mps = 0.4;
  /// Lower bound on the time between waypoints (also used when waypoints coincide).
  double min_segment_duration_s = 0.5;
  HandJitterConfig jitter;
  /// > 0: the camera first stands still this long at the first waypoint (no sway: resting on
  /// something, as a robot or a VIO rig does before it starts), then the sway fades in over
  /// kSwayFadeIn_s (a C2 ramp, so velocity and acceleration stay continuous). 0: the path starts
  /// at once and the sway is on from t = 0 (the behaviour of every earlier recording).
  double rest_at_start_s = 0.0;
  static constexpr double kSwayFadeIn_s = 1.0;

  /// Throws InputError naming the first bad field.
  void validate() const;
};

/// Kinematic state of the camera (frame C: optical axis +z, x right, y down) at one time.
struct TrajectoryState {
  double t_s = 0.0;
  Eigen::Isometry3d T_W_C = Eigen::Isometry3d::Identity();
  Eigen::Vector3d velocity_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d acceleration_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity_C = Eigen::Vector3d::Zero();      // omega with R^T dR/dt = [w]x
  Eigen::Vector3d angular_acceleration_C = Eigen::Vector3d::Zero();  // d/dt of the above
};

/// Thread safety: const methods may be called from several threads at once.
class Trajectory {
 public:
  /// Throws InputError for fewer than 2 waypoints, non-finite values or a vertical view.
  Trajectory(const std::vector<Waypoint>& waypoints, const TrajectoryConfig& config,
             std::uint64_t seed);

  double duration_s() const { return rest_s_ + position_.duration_s(); }
  /// Camera-to-world pose; t is clamped to [0, duration].
  Eigen::Isometry3d pose(double t_s) const;
  /// Pose and derivatives; t is clamped to [0, duration]. Translation derivatives are exact;
  /// rotation derivatives are 5-point central differences (error ~1e-12 rad/s).
  TrajectoryState state(double t_s) const;
  /// Times k / rate_hz for k = 0, 1, ... up to the duration.
  std::vector<double> sampleTimes(double rate_hz) const;
  /// Poses at sampleTimes(rate_hz).
  std::vector<Eigen::Isometry3d> sample(double rate_hz) const;

 private:
  Eigen::Matrix3d rotation(double t_s) const;  // unclamped (splines extrapolate smoothly)
  Eigen::Vector3d position(double t_s, int derivative) const;
  /// Spline time (0 during the rest) and the sway's weight and its derivatives at t.
  double splineTime(double t_s) const { return rest_s_ > 0.0 ? std::max(0.0, t_s - rest_s_) : t_s; }
  Eigen::Vector3d swayWeight(double t_s) const;

  double rest_s_ = 0.0;
  QuinticBSpline position_;
  QuinticBSpline look_at_;
  HandJitter jitter_;
};

}  // namespace strata::sim
