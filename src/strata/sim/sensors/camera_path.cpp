#include "strata/sim/sensors/camera_path.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "strata/core/error.h"
#include "strata/sim/default_scene.h"  // lookAt

namespace strata::sim {
namespace {

// Step of the rotation finite differences: truncation ~h^4 |R^(5)| / 30, round-off ~eps / h^2.
constexpr double kRotationStep_s = 1e-3;

Eigen::Vector3d vee(const Eigen::Matrix3d& M) {  // of the skew-symmetric part
  return 0.5 * Eigen::Vector3d(M(2, 1) - M(1, 2), M(0, 2) - M(2, 0), M(1, 0) - M(0, 1));
}

std::vector<Eigen::Vector3d> positionsOf(const std::vector<Waypoint>& waypoints) {
  std::vector<Eigen::Vector3d> out;
  for (const Waypoint& w : waypoints) out.push_back(w.position_W);
  return out;
}

std::vector<Eigen::Vector3d> targetsOf(const std::vector<Waypoint>& waypoints) {
  std::vector<Eigen::Vector3d> out;
  for (const Waypoint& w : waypoints) out.push_back(w.look_at_W);
  return out;
}

double segmentDuration(const std::vector<Waypoint>& waypoints, const TrajectoryConfig& config) {
  config.validate();
  if (waypoints.size() < 2) throw InputError("Trajectory: needs at least 2 waypoints");
  double length = 0.0;
  for (std::size_t k = 0; k < waypoints.size(); ++k) {
    const Waypoint& w = waypoints[k];
    if (!w.position_W.allFinite() || !w.look_at_W.allFinite()) {
      throw InputError("Trajectory: waypoint " + std::to_string(k) + " is not finite");
    }
    lookAt(w.position_W, w.look_at_W);  // throws for a vertical view
    if (k > 0) length += (w.position_W - waypoints[k - 1].position_W).norm();
  }
  const double mean_spacing = length / static_cast<double>(waypoints.size() - 1);
  return std::max(config.min_segment_duration_s, mean_spacing / config.mean_speed_mps);
}

}  // namespace

void TrajectoryConfig::validate() const {
  if (!(mean_speed_mps > 0.0) || !std::isfinite(mean_speed_mps)) {
    throw InputError("TrajectoryConfig: mean_speed_mps must be positive and finite");
  }
  if (!(min_segment_duration_s > 0.0) || !std::isfinite(min_segment_duration_s)) {
    throw InputError("TrajectoryConfig: min_segment_duration_s must be positive and finite");
  }
  if (!(rest_at_start_s >= 0.0) || !std::isfinite(rest_at_start_s)) {
    throw InputError("TrajectoryConfig: rest_at_start_s must be >= 0 and finite");
  }
  jitter.validate();
}

Trajectory::Trajectory(const std::vector<Waypoint>& waypoints, const TrajectoryConfig& config,
                       std::uint64_t seed)
    : rest_s_(config.rest_at_start_s),
      position_(positionsOf(waypoints), segmentDuration(waypoints, config)),
      look_at_(targetsOf(waypoints), segmentDuration(waypoints, config)),
      jitter_(config.jitter, seed) {}

Eigen::Vector3d Trajectory::swayWeight(double t_s) const {
  if (rest_s_ <= 0.0) return {1.0, 0.0, 0.0};
  const double T = TrajectoryConfig::kSwayFadeIn_s;
  const double x = (t_s - rest_s_) / T;
  if (x <= 0.0) return Eigen::Vector3d::Zero();
  if (x >= 1.0) return {1.0, 0.0, 0.0};
  // smootherstep 6x^5 - 15x^4 + 10x^3 and its first two derivatives in t.
  return {x * x * x * (x * (6.0 * x - 15.0) + 10.0), 30.0 * x * x * (x - 1.0) * (x - 1.0) / T,
          60.0 * x * (2.0 * x - 1.0) * (x - 1.0) / (T * T)};
}

Eigen::Vector3d Trajectory::position(double t_s, int derivative) const {
  const Eigen::Vector3d spline = rest_s_ > 0.0 && t_s < rest_s_ && derivative > 0
                                     ? Eigen::Vector3d::Zero()
                                     : position_.evaluate(splineTime(t_s), derivative);
  // The sway runs on the spline's clock; product rule for its fade-in weight w(t).
  const Eigen::Vector3d w = swayWeight(t_s);
  const double ts = splineTime(t_s);
  Eigen::Vector3d sway = w[0] * jitter_.translation(ts, derivative);
  if (derivative >= 1 && w[1] != 0.0) {
    sway += (derivative == 1 ? 1.0 : 2.0) * w[1] * jitter_.translation(ts, derivative - 1);
  }
  if (derivative == 2 && w[2] != 0.0) sway += w[2] * jitter_.translation(ts, 0);
  return spline + sway;
}

Eigen::Matrix3d Trajectory::rotation(double t_s) const {
  // R_W_C = R_lookat(p(t), target(t)) * Exp(theta_jitter(t)).
  const double ts = splineTime(t_s);
  const Eigen::Matrix3d R_look = lookAt(position_.evaluate(ts), look_at_.evaluate(ts)).linear();
  const Eigen::Vector3d theta = swayWeight(t_s)[0] * jitter_.rotation(ts);
  const double angle = theta.norm();
  const Eigen::Matrix3d R_jitter = angle > 0.0
                                       ? Eigen::AngleAxisd(angle, theta / angle).toRotationMatrix()
                                       : Eigen::Matrix3d::Identity();
  return R_look * R_jitter;
}

Eigen::Isometry3d Trajectory::pose(double t_s) const {
  t_s = std::clamp(t_s, 0.0, duration_s());
  Eigen::Isometry3d T_W_C = Eigen::Isometry3d::Identity();
  T_W_C.linear() = rotation(t_s);
  T_W_C.translation() = position(t_s, 0);
  return T_W_C;
}

TrajectoryState Trajectory::state(double t_s) const {
  t_s = std::clamp(t_s, 0.0, duration_s());
  TrajectoryState s;
  s.t_s = t_s;
  s.T_W_C = pose(t_s);
  s.velocity_W = position(t_s, 1);
  s.acceleration_W = position(t_s, 2);
  // 5-point stencils: f' = (f-2 - 8 f-1 + 8 f+1 - f+2) / 12h,
  // f'' = (-f-2 + 16 f-1 - 30 f0 + 16 f+1 - f+2) / 12h^2.
  const double h = kRotationStep_s;
  const Eigen::Matrix3d Rm2 = rotation(t_s - 2 * h), Rm1 = rotation(t_s - h);
  const Eigen::Matrix3d Rp1 = rotation(t_s + h), Rp2 = rotation(t_s + 2 * h);
  const Eigen::Matrix3d R = s.T_W_C.linear();
  const Eigen::Matrix3d dR = (Rm2 - 8.0 * Rm1 + 8.0 * Rp1 - Rp2) / (12.0 * h);
  const Eigen::Matrix3d ddR = (-Rm2 + 16.0 * Rm1 - 30.0 * R + 16.0 * Rp1 - Rp2) / (12.0 * h * h);
  s.angular_velocity_C = vee(R.transpose() * dR);  // [w]x = R^T dR/dt
  // d/dt (R^T dR) = dR^T dR + R^T ddR; its skew part is [dw/dt]x.
  s.angular_acceleration_C = vee(dR.transpose() * dR + R.transpose() * ddR);
  return s;
}

std::vector<double> Trajectory::sampleTimes(double rate_hz) const {
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) {
    throw InputError("Trajectory::sample: rate_hz must be positive and finite");
  }
  const auto count = static_cast<long long>(std::floor(duration_s() * rate_hz + 1e-9)) + 1;
  std::vector<double> times(static_cast<std::size_t>(count));
  for (long long k = 0; k < count; ++k) times[k] = static_cast<double>(k) / rate_hz;
  return times;
}

std::vector<Eigen::Isometry3d> Trajectory::sample(double rate_hz) const {
  std::vector<Eigen::Isometry3d> poses;
  for (double t : sampleTimes(rate_hz)) poses.push_back(pose(t));
  return poses;
}

}  // namespace strata::sim
