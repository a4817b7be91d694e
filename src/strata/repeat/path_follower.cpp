#include "strata/repeat/path_follower.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "strata/core/error.h"
#include "strata/repeat/taught_route.h"

namespace strata::repeat {
namespace {

/// Shapes the reference only: the taught path was flown, and the path ahead is checked against
/// the live map separately (repeat_loop.h).
class OpenSpace final : public plan::CollisionChecker {
 public:
  std::vector<std::uint8_t> spheresFree(const std::vector<Eigen::Vector3f>& centres_W, float,
                                        UnknownPolicy) override {
    return std::vector<std::uint8_t>(centres_W.size(), 1);
  }
  std::vector<EsdfSample> sample(const std::vector<Eigen::Vector3f>& points_W) override {
    std::vector<EsdfSample> out(points_W.size());
    for (EsdfSample& s : out) {
      s.distance_m = maxDistance();
      s.status = EsdfStatus::kKnown;
    }
    return out;
  }
  float voxelSize() const override { return 0.05f; }
  float maxDistance() const override { return 10.0f; }
};

}  // namespace

void FollowerConfig::validate() const {
  for (double v :
       {horizon_m, replan_period_s, max_lag_m, turn_in_place_rad, slow_speed_mps, search_ahead_m}) {
    if (!(v > 0.0) || !std::isfinite(v)) throw InputError("follower settings must be > 0");
  }
  if (!(behind_m >= 0.0) || !(search_back_m >= 0.0)) {
    throw InputError("follower behind_m and search_back_m must be >= 0");
  }
  if (!(reference_share > 0.0f && reference_share <= 1.0f)) {
    throw InputError("follower reference_share must be in (0, 1]");
  }
  if (!(position_gain_per_s > 0.0f) || !(yaw_gain_per_s > 0.0f) || !(goal_tolerance_m > 0.0f) ||
      !(simplify_tolerance_m >= 0.0f)) {
    throw InputError("follower gains and tolerances must be > 0");
  }
}

PathFollower::PathFollower(const TaughtPath& path, const FollowerConfig& config,
                           const explore::RobotConfig& robot)
    : path_(path), config_(config), robot_(robot) {
  config_.validate();
  robot_.validate();
  if (path_.p_M.size() < 2) throw InputError("the taught path holds fewer than 2 poses");
}

void PathFollower::updateProgress(const Eigen::Vector3f& p_M) {
  if (onDetour()) return;
  // Cost: distance plus a little per metre of arc away from the last progress point, so that
  // where the path turns back on itself the earlier pass wins a tie.
  const double lo = progress_m_ - config_.search_back_m, hi = progress_m_ + config_.search_ahead_m;
  double best_cost = std::numeric_limits<double>::infinity(), best_s = progress_m_;
  for (std::size_t i = 1; i < path_.p_M.size(); ++i) {
    if (path_.s_m[i] < lo || path_.s_m[i - 1] > hi) continue;
    const Eigen::Vector3f a = path_.p_M[i - 1], ab = path_.p_M[i] - a;
    const float l2 = ab.squaredNorm();
    const float f = l2 > 0.0f ? std::clamp((p_M - a).dot(ab) / l2, 0.0f, 1.0f) : 0.0f;
    const double s = std::clamp(path_.s_m[i - 1] + f * (path_.s_m[i] - path_.s_m[i - 1]), lo, hi);
    const double cost = (path_.at(s) - p_M).norm() + 0.05 * std::abs(s - progress_m_);
    if (cost < best_cost) {
      best_cost = cost;
      best_s = s;
    }
  }
  progress_m_ = std::clamp(best_s, 0.0, path_.length_m());
}

void PathFollower::setDetour(std::vector<Eigen::Vector3f> detour_M, double resume_m) {
  detour_M_ = std::move(detour_M);
  resume_m_ = std::clamp(resume_m, 0.0, path_.length_m());
  if (detour_M_.empty()) return;
  // One reference for the whole detour and a little of the taught path after it.
  std::vector<Eigen::Vector3f> polyline;
  for (const Eigen::Vector3f& q : detour_M_) {
    if (polyline.empty() || (q - polyline.back()).norm() > 1e-3f) polyline.push_back(q);
  }
  const std::vector<Eigen::Vector3f> after = path_.between(resume_m_, resume_m_ + 2.0);
  polyline.insert(polyline.end(), after.begin() + 1, after.end());
  shape(polyline);
  tau_s_ = 0.0;
}

void PathFollower::shape(const std::vector<Eigen::Vector3f>& polyline) {
  plan::TrajectoryLimits limits;
  limits.v_max_mps = config_.reference_share * robot_.max_speed_mps;
  limits.a_max_mps2 = config_.reference_share * robot_.max_accel_mps2;
  OpenSpace open;
  reference_ = plan::makeTrajectory(simplifyPolyline(polyline, config_.simplify_tolerance_m),
                                    limits, open, robot_.radius_m, UnknownPolicy::kFree);
}

void PathFollower::rebuild(const Eigen::Vector3f& p_M, double t_s) {
  shape(path_.between(std::max(0.0, progress_m_ - config_.behind_m),
                      progress_m_ + config_.horizon_m));
  // The reference time of the robot: the nearest sample within the first part (behind the
  // robot and a little ahead), the earliest of equals (where the path turns back on itself).
  tau_s_ = 0.0;
  float best = std::numeric_limits<float>::infinity();
  double arc = 0.0;
  for (std::size_t i = 0; i < reference_.samples.size(); ++i) {
    if (i > 0) arc += (reference_.samples[i].p_W - reference_.samples[i - 1].p_W).norm();
    if (arc > config_.behind_m + 1.0) break;
    const float d = (reference_.samples[i].p_W - p_M).norm();
    if (d < best - 1e-4f) {
      best = d;
      tau_s_ = reference_.samples[i].t_s;
    }
  }
  next_build_s_ = t_s + config_.replan_period_s;
}

FollowerCommand PathFollower::command(const Eigen::Vector3f& p_M, float yaw_rad, double t_s) {
  const double dt = last_command_s_ ? std::max(0.0, t_s - *last_command_s_) : 0.0;
  last_command_s_ = t_s;
  updateProgress(p_M);
  if (onDetour()) {
    // Back on the taught path once at the detour's end.
    if ((p_M - detour_M_.back()).norm() < 0.3f || tau_s_ >= reference_.duration_s) {
      progress_m_ = resume_m_;
      detour_M_.clear();
      rebuild(p_M, t_s);
    }
  } else if (t_s >= next_build_s_ || reference_.samples.empty()) {
    rebuild(p_M, t_s);
  }
  FollowerCommand c;
  if (!onDetour() && progress_m_ >= path_.length_m() - 1e-3 - config_.goal_tolerance_m &&
      (p_M - path_.p_M.back()).norm() < config_.goal_tolerance_m) {
    c.done = true;
    return c;
  }
  const plan::TrajectorySample ref = reference_.at(tau_s_);
  float heading = yaw_rad;
  const bool ahead = headingAt(reference_, tau_s_, heading);
  const float yaw_error = explore::wrapAngle(heading - yaw_rad);
  const bool turn_first = ahead && std::abs(yaw_error) > config_.turn_in_place_rad &&
                          ref.v_W.norm() < config_.slow_speed_mps;
  const Eigen::Vector3f offset = ref.p_W - p_M;
  c.v_M = config_.position_gain_per_s * offset;
  if (!turn_first) {
    c.v_M += ref.v_W;
    // The reference waits for a robot that lags (e.g. after a correction of the estimate).
    const double rate = offset.norm() > config_.max_lag_m ? 0.2 : 1.0;
    tau_s_ = std::min(reference_.duration_s, tau_s_ + rate * dt);
  }
  const float max_rate = robot_.max_yaw_rate_radps;
  c.yaw_rate_radps = std::clamp(config_.yaw_gain_per_s * yaw_error, -max_rate, max_rate);
  return c;
}

std::vector<Eigen::Vector3f> PathFollower::ahead(float length_m) const {
  std::vector<Eigen::Vector3f> out;
  if (reference_.samples.empty()) return out;
  float left = length_m;
  out.push_back(reference_.at(tau_s_).p_W);
  for (const plan::TrajectorySample& s : reference_.samples) {
    if (s.t_s <= tau_s_) continue;
    if (left <= 0.0f) break;
    left -= (s.p_W - out.back()).norm();
    out.push_back(s.p_W);
  }
  return out;
}

}  // namespace strata::repeat
