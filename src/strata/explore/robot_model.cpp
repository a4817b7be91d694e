#include "strata/explore/robot_model.h"

#include <algorithm>
#include <cmath>

#include "strata/core/error.h"

namespace strata::explore {
namespace {

bool positiveFinite(float v) { return std::isfinite(v) && v > 0.0f; }

}  // namespace

void RobotConfig::validate() const {
  if (!positiveFinite(max_speed_mps)) throw InputError("robot max_speed_mps must be > 0");
  if (!positiveFinite(max_accel_mps2)) throw InputError("robot max_accel_mps2 must be > 0");
  if (!positiveFinite(max_yaw_rate_radps)) {
    throw InputError("robot max_yaw_rate_radps must be > 0");
  }
  if (!positiveFinite(radius_m)) throw InputError("robot radius_m must be > 0");
}

float wrapAngle(float angle_rad) {
  constexpr float kTwoPi = 6.28318530718f;
  float a = std::fmod(angle_rad + 3.14159265359f, kTwoPi);
  if (a < 0.0f) a += kTwoPi;
  return a - 3.14159265359f;
}

TrapezoidProfile::TrapezoidProfile(double length_m, double max_speed_mps, double max_accel_mps2)
    : length_m_(std::max(0.0, length_m)), accel_mps2_(max_accel_mps2) {
  // Distance to reach full speed; a segment shorter than twice that never cruises.
  const double accel_distance_m = 0.5 * max_speed_mps * max_speed_mps / max_accel_mps2;
  if (2.0 * accel_distance_m >= length_m_) {
    accel_time_s_ = std::sqrt(length_m_ / max_accel_mps2);
    peak_speed_mps_ = max_accel_mps2 * accel_time_s_;
    cruise_time_s_ = 0.0;
  } else {
    accel_time_s_ = max_speed_mps / max_accel_mps2;
    peak_speed_mps_ = max_speed_mps;
    cruise_time_s_ = (length_m_ - 2.0 * accel_distance_m) / max_speed_mps;
  }
}

double TrapezoidProfile::distanceAt(double t_s) const {
  const double t = std::clamp(t_s, 0.0, duration());
  const double ta = accel_time_s_;
  if (t <= ta) return 0.5 * accel_mps2_ * t * t;
  const double d_accel = 0.5 * accel_mps2_ * ta * ta;
  if (t <= ta + cruise_time_s_) return d_accel + peak_speed_mps_ * (t - ta);
  const double tb = duration() - t;  // time left braking
  return length_m_ - 0.5 * accel_mps2_ * tb * tb;
}

double TrapezoidProfile::speedAt(double t_s) const {
  const double t = std::clamp(t_s, 0.0, duration());
  if (t <= accel_time_s_) return accel_mps2_ * t;
  if (t <= accel_time_s_ + cruise_time_s_) return peak_speed_mps_;
  return accel_mps2_ * (duration() - t);
}

PathFollower::PathFollower(const RobotConfig& config, const RobotPose& start)
    : config_(config), pose_(start) {
  config_.validate();
  pose_.yaw_rad = wrapAngle(pose_.yaw_rad);
}

void PathFollower::setPath(std::vector<Waypoint> path) {
  path_ = std::move(path);
  next_ = 0;
  phase_ = Phase::kIdle;
  speed_mps_ = 0.0;
  beginNext();
}

void PathFollower::hover(double duration_s) {
  path_.clear();
  next_ = 0;
  speed_mps_ = 0.0;
  phase_ = duration_s > 0.0 ? Phase::kHovering : Phase::kIdle;
  phase_time_s_ = duration_s;
}

std::vector<Waypoint> PathFollower::remaining() const {
  return {path_.begin() + static_cast<std::ptrdiff_t>(std::min(next_, path_.size())), path_.end()};
}

void PathFollower::beginNext() {
  if (next_ >= path_.size()) {
    phase_ = Phase::kIdle;
    return;
  }
  segment_start_W_ = pose_.position_W;
  const double length_m = (path_[next_].position_W - segment_start_W_).norm();
  profile_ = TrapezoidProfile(length_m, config_.max_speed_mps, config_.max_accel_mps2);
  phase_time_s_ = 0.0;
  phase_ = Phase::kMoving;
}

double PathFollower::brake() {
  if (phase_ == Phase::kMoving && speed_mps_ > 0.0) {
    // Straight segments: the direction of travel is the segment's.
    brake_dir_W_ = (path_[next_].position_W - segment_start_W_).normalized();
    brake_start_W_ = pose_.position_W;
    brake_speed_mps_ = speed_mps_;
    phase_time_s_ = 0.0;
    phase_ = Phase::kBraking;
  } else if (phase_ != Phase::kBraking) {
    phase_ = Phase::kIdle;
    speed_mps_ = 0.0;
  }
  path_.clear();
  next_ = 0;
  return 0.5 * speed_mps_ * speed_mps_ / config_.max_accel_mps2;
}

double PathFollower::advanceBraking(double dt_s) {
  const double a = config_.max_accel_mps2;
  const double stop_s = brake_speed_mps_ / a;
  const double used = std::min(dt_s, stop_s - phase_time_s_);
  phase_time_s_ += used;
  const double t = phase_time_s_;
  const double s = brake_speed_mps_ * t - 0.5 * a * t * t;
  pose_.position_W = brake_start_W_ + brake_dir_W_ * static_cast<float>(s);
  speed_mps_ = std::max(0.0, brake_speed_mps_ - a * t);
  if (phase_time_s_ >= stop_s - 1e-12) {
    speed_mps_ = 0.0;
    phase_ = Phase::kIdle;
  }
  return dt_s - used;
}

double PathFollower::turnYaw(double dt_s, float target_yaw_rad) {
  const float error = wrapAngle(target_yaw_rad - pose_.yaw_rad);
  const double max_turn = config_.max_yaw_rate_radps * dt_s;
  if (std::abs(error) <= max_turn) {
    pose_.yaw_rad = wrapAngle(target_yaw_rad);
    return dt_s - std::abs(error) / config_.max_yaw_rate_radps;
  }
  pose_.yaw_rad = wrapAngle(pose_.yaw_rad + static_cast<float>(std::copysign(max_turn, error)));
  return 0.0;
}

void PathFollower::advance(double dt_s) {
  double left_s = std::max(0.0, dt_s);
  // Phases may end inside the step: the time left over goes on to the next phase.
  while (left_s > 1e-12) {
    if (phase_ == Phase::kIdle) {
      speed_mps_ = 0.0;
      return;
    }
    if (phase_ == Phase::kHovering) {
      const double used = std::min(left_s, phase_time_s_);
      phase_time_s_ -= used;
      left_s -= used;
      if (phase_time_s_ <= 0.0) phase_ = Phase::kIdle;
      continue;
    }
    if (phase_ == Phase::kBraking) {
      left_s = advanceBraking(left_s);
      continue;
    }
    const Waypoint& target = path_[next_];
    if (phase_ == Phase::kMoving) {
      const double used = std::min(left_s, profile_.duration() - phase_time_s_);
      phase_time_s_ += used;
      turnYaw(used, target.yaw_rad);
      const Eigen::Vector3f delta = target.position_W - segment_start_W_;
      const float length = delta.norm();
      const float s = static_cast<float>(profile_.distanceAt(phase_time_s_));
      pose_.position_W = length > 0.0f ? Eigen::Vector3f(segment_start_W_ + delta * (s / length))
                                       : Eigen::Vector3f(target.position_W);
      speed_mps_ = profile_.speedAt(phase_time_s_);
      left_s -= used;
      if (phase_time_s_ >= profile_.duration()) {
        pose_.position_W = target.position_W;
        speed_mps_ = 0.0;
        phase_ = Phase::kTurning;
      }
      continue;
    }
    // kTurning: at the waypoint, turn in place to its yaw, then on to the next waypoint.
    left_s = turnYaw(left_s, target.yaw_rad);
    if (std::abs(wrapAngle(target.yaw_rad - pose_.yaw_rad)) < 1e-6f) {
      ++next_;
      beginNext();
    }
  }
}

}  // namespace strata::explore
