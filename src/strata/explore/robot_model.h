#pragma once
// The simulated robot of exploration: a MAV that is a sphere (position + yaw, camera looking
// along the yaw, horizontal) flying a path of waypoints. Each segment is flown in a straight
// line with a trapezoidal speed profile (accelerate at max_accel, cruise at max_speed, brake to
// a stop at the waypoint); meanwhile the yaw turns towards the waypoint's target yaw at
// max_yaw_rate, and at the waypoint the robot turns in place until the yaw is reached. brake()
// abandons the path: the robot decelerates at max_accel along its segment to rest (yaw held).
// Time is simulated: advance(dt) moves the robot by dt seconds.
// Frames: world (z up), metres, seconds; yaw counter-clockwise about +z from +x, radians.
// Thread safety: none (plain value types).
#include <Eigen/Core>
#include <vector>

namespace strata::explore {

struct RobotConfig {
  float max_speed_mps = 1.0f;
  float max_accel_mps2 = 1.0f;
  float max_yaw_rate_radps = 0.75f;
  /// The robot is a sphere of this radius (metres); collisions are judged against it.
  float radius_m = 0.3f;

  /// Throws InputError naming the bad field.
  void validate() const;
};

struct RobotPose {
  Eigen::Vector3f position_W = Eigen::Vector3f::Zero();
  float yaw_rad = 0.0f;
};

struct Waypoint {
  Eigen::Vector3f position_W = Eigen::Vector3f::Zero();
  float yaw_rad = 0.0f;
};

/// Wraps an angle to (-pi, pi].
float wrapAngle(float angle_rad);

/// Rest-to-rest trapezoidal (or, when too short to cruise, triangular) speed profile over a
/// straight segment of length_m.
struct TrapezoidProfile {
  TrapezoidProfile(double length_m, double max_speed_mps, double max_accel_mps2);
  double duration() const { return 2.0 * accel_time_s_ + cruise_time_s_; }
  /// Distance travelled after t seconds (clamped to [0, duration()]).
  double distanceAt(double t_s) const;
  double speedAt(double t_s) const;

 private:
  double length_m_, accel_mps2_, peak_speed_mps_, accel_time_s_, cruise_time_s_;
};

/// Flies a path from the current pose. Waypoints are taken in order; a new path replaces the old
/// one (call setPath only when atWaypoint(): the robot is at rest there).
class PathFollower {
 public:
  PathFollower(const RobotConfig& config, const RobotPose& start);

  void setPath(std::vector<Waypoint> path);
  /// Stay in place for duration_s (hovering), e.g. when the planner has nothing to fly.
  void hover(double duration_s);
  /// Abandons the rest of the path: decelerates at max_accel_mps2 along the current segment to
  /// rest (at once when not moving), yaw held. Returns the distance still flown while braking
  /// (metres). done() once at rest.
  double brake();
  /// Moving along a segment (not braking, turning or hovering).
  bool moving() const { return phase_ == Phase::kMoving; }
  /// Moves the simulated robot by dt_s seconds.
  void advance(double dt_s);

  const RobotPose& pose() const { return pose_; }
  double speed() const { return speed_mps_; }
  /// Every waypoint reached (and hovering over).
  bool done() const { return next_ >= path_.size() && phase_ == Phase::kIdle; }
  /// At rest between segments (a waypoint reached with its yaw, or done): a new path may start.
  bool atWaypoint() const { return phase_ == Phase::kIdle; }
  /// Waypoints not yet reached.
  std::vector<Waypoint> remaining() const;
  const RobotConfig& config() const { return config_; }

 private:
  enum class Phase { kIdle, kMoving, kBraking, kTurning, kHovering };
  /// Turns towards target_yaw_rad for at most dt_s; returns the time left over once reached.
  double turnYaw(double dt_s, float target_yaw_rad);
  void beginNext();
  /// kBraking for at most dt_s; returns the time left over once at rest.
  double advanceBraking(double dt_s);

  RobotConfig config_;
  RobotPose pose_;
  std::vector<Waypoint> path_;
  std::size_t next_ = 0;  // waypoint being flown to
  Phase phase_ = Phase::kIdle;
  Eigen::Vector3f segment_start_W_ = Eigen::Vector3f::Zero();
  TrapezoidProfile profile_{0.0, 1.0, 1.0};
  double phase_time_s_ = 0.0;  // time into the segment (kMoving) or hover left (kHovering)
  double speed_mps_ = 0.0;
  // kBraking: from brake_start_W_ along brake_dir_W_ at brake_speed_mps_ when the brake began.
  Eigen::Vector3f brake_start_W_ = Eigen::Vector3f::Zero();
  Eigen::Vector3f brake_dir_W_ = Eigen::Vector3f::Zero();
  double brake_speed_mps_ = 0.0;
};

}  // namespace strata::explore
