#pragma once
// The repeat's follower: turns the taught path (map frame) into a time-parameterised reference
// over a receding horizon and commands the robot so that its ESTIMATED pose follows it.
// Horizon: the taught path from behind_m behind to horizon_m ahead of the progress point (the
// taught point nearest the estimate, searched in a window around the last one so that a path
// that turns back on itself is followed in order), simplified (2 cm), then
// plan::makeTrajectory (speed, tangential and centripetal acceleration limits; from rest at its
// start, which lies behind the robot, so the robot flies at speed through the joins). Rebuilt
// every replan_period_s. A detour (setDetour) replaces the taught path up to a resume point.
// Command: the robot's time on the reference starts at the sample nearest the estimate when the
// reference is built and runs with the clock (slower while the robot lags); the command is the
// reference's velocity at that time plus position_gain times the offset to its position; yaw
// towards the heading of the reference ahead, turning in place first (reference time held) where
// it is off by more than turn_in_place_rad while the reference is slow, as the teach did.
// Frames: map M (z up); metres, seconds, radians. Thread safety: none (one owner).
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "strata/explore/robot_model.h"
#include "strata/plan/flight_trajectory.h"
#include "strata/repeat/taught_path.h"

namespace strata::repeat {

struct FollowerConfig {
  double horizon_m = 5.0;
  double behind_m = 1.0;
  double replan_period_s = 0.5;
  /// Window of the progress search around the last progress point (arc length, metres): the
  /// progress never goes back by more than search_back_m (0: monotone), so that where the path
  /// turns back on itself the pass being flown is the one followed.
  double search_back_m = 0.0;
  double search_ahead_m = 1.0;
  /// The reference time advances at a fifth of the clock while the estimate is farther than
  /// this from the reference (metres).
  double max_lag_m = 0.25;
  /// The reference is timed at this share of the robot's speed and acceleration limits, leaving
  /// the rest to the feedback (a reference at the limits is followed with a lag at corners).
  float reference_share = 0.75f;
  float position_gain_per_s = 2.5f;
  float yaw_gain_per_s = 2.0f;
  double turn_in_place_rad = 0.5;
  double slow_speed_mps = 0.15;
  float simplify_tolerance_m = 0.02f;
  /// Done within this distance of the path's end (metres).
  float goal_tolerance_m = 0.15f;
  void validate() const;
};

struct FollowerCommand {
  Eigen::Vector3f v_M = Eigen::Vector3f::Zero();  // velocity wanted of the estimate
  float yaw_rate_radps = 0.0f;
  bool done = false;
};

class PathFollower {
 public:
  /// `path` must outlive the follower.
  PathFollower(const TaughtPath& path, const FollowerConfig& config,
               const explore::RobotConfig& robot);

  /// The command for the estimate at p_M with yaw_rad at simulated time t_s.
  FollowerCommand command(const Eigen::Vector3f& p_M, float yaw_rad, double t_s);
  /// The reference ahead of the robot's nearest reference sample, length_m of it.
  std::vector<Eigen::Vector3f> ahead(float length_m) const;
  /// Progress along the taught path (arc length, metres).
  double progress_m() const { return progress_m_; }
  /// Flies `detour_M` (from the robot's estimate onwards, one reference for all of it), then the
  /// taught path from resume_m on.
  void setDetour(std::vector<Eigen::Vector3f> detour_M, double resume_m);
  bool onDetour() const { return !detour_M_.empty(); }
  /// The reference is rebuilt at the next command (e.g. after a stop).
  void invalidate() { next_build_s_ = -1.0; }

 private:
  void updateProgress(const Eigen::Vector3f& p_M);
  void rebuild(const Eigen::Vector3f& p_M, double t_s);
  /// The reference along `polyline` (simplified, then plan::makeTrajectory).
  void shape(const std::vector<Eigen::Vector3f>& polyline);

  const TaughtPath& path_;
  FollowerConfig config_;
  explore::RobotConfig robot_;
  double progress_m_ = 0.0;
  std::vector<Eigen::Vector3f> detour_M_;
  double resume_m_ = 0.0;
  plan::Trajectory reference_;
  double tau_s_ = 0.0;  // the robot's time on the reference
  std::optional<double> last_command_s_;
  double next_build_s_ = -1.0;
};

}  // namespace strata::repeat
