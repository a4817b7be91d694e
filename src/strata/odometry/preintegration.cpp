#include "strata/odometry/preintegration.h"

#include <cmath>
#include <string>

#include "strata/core/error.h"
#include "strata/odometry/so3.h"

namespace strata::odometry {
namespace {

void requireNonNegative(double value, const char* field) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    throw InputError(std::string("ImuNoise: ") + field + " must be finite and >= 0");
  }
}

}  // namespace

void ImuNoise::validate() const {
  requireNonNegative(gyro_noise_density, "gyro_noise_density");
  requireNonNegative(gyro_random_walk, "gyro_random_walk");
  requireNonNegative(accel_noise_density, "accel_noise_density");
  requireNonNegative(accel_random_walk, "accel_random_walk");
}

ImuMeasurement interpolate(const ImuMeasurement& a, const ImuMeasurement& b, double t_s) {
  const double span = b.t_s - a.t_s;
  const double w = span > 0.0 ? (t_s - a.t_s) / span : 0.0;
  ImuMeasurement m;
  m.t_s = t_s;
  m.gyro_rad_s = (1.0 - w) * a.gyro_rad_s + w * b.gyro_rad_s;
  m.accel_mps2 = (1.0 - w) * a.accel_mps2 + w * b.accel_mps2;
  return m;
}

Preintegration::Preintegration(const ImuBias& bias, const ImuNoise& noise)
    : bias_(bias), noise_(noise) {
  noise_.validate();
  reset();
}

void Preintegration::reset() {
  dt_s_ = 0.0;
  dR_.setIdentity();
  dv_.setZero();
  dp_.setZero();
  cov_.setZero();
  dR_dbg_.setZero();
  dv_dbg_.setZero();
  dv_dba_.setZero();
  dp_dbg_.setZero();
  dp_dba_.setZero();
}

void Preintegration::integrate(const ImuMeasurement& a, const ImuMeasurement& b) {
  const double dt = b.t_s - a.t_s;
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    throw InputError("Preintegration: IMU samples at t=" + std::to_string(a.t_s) +
                     " and t=" + std::to_string(b.t_s) + " are not increasing in time");
  }
  if (!a.gyro_rad_s.allFinite() || !a.accel_mps2.allFinite() || !b.gyro_rad_s.allFinite() ||
      !b.accel_mps2.allFinite()) {
    throw InputError("Preintegration: non-finite IMU sample at t=" + std::to_string(a.t_s));
  }
  samples_.push_back(a);
  samples_.push_back(b);
  step(a, b);
}

void Preintegration::step(const ImuMeasurement& a, const ImuMeasurement& b) {
  const double dt = b.t_s - a.t_s;
  const Eigen::Vector3d omega = 0.5 * (a.gyro_rad_s + b.gyro_rad_s) - bias_.gyro_rad_s;
  const Eigen::Matrix3d dR_step = expSO3(omega * dt);
  const Eigen::Matrix3d dR_next = dR_ * dR_step;
  // Mean acceleration over the step in frame i (midpoint), and the same in frame k for the
  // linearised recursions (which are written with dR_k * acc_k).
  const Eigen::Vector3d acc_i =
      0.5 * (dR_ * (a.accel_mps2 - bias_.accel_mps2) + dR_next * (b.accel_mps2 - bias_.accel_mps2));
  const Eigen::Vector3d acc_k = dR_.transpose() * acc_i;
  const Eigen::Matrix3d acc_skew = skew(acc_k);
  const Eigen::Matrix3d Jr = rightJacobianSO3(omega * dt);
  const double dt2 = dt * dt;

  // Covariance, Eq. (62)-(63): eta_{k+1} = A eta_k + B n_gd + C n_ad, Sigma_d = sigma^2 / dt.
  Eigen::Matrix<double, 9, 9> A = Eigen::Matrix<double, 9, 9>::Identity();
  A.block<3, 3>(0, 0) = dR_step.transpose();
  A.block<3, 3>(3, 0) = -dR_ * acc_skew * dt;
  A.block<3, 3>(6, 0) = -0.5 * dR_ * acc_skew * dt2;
  A.block<3, 3>(6, 3) = Eigen::Matrix3d::Identity() * dt;
  Eigen::Matrix<double, 9, 3> B = Eigen::Matrix<double, 9, 3>::Zero();
  B.block<3, 3>(0, 0) = Jr * dt;
  Eigen::Matrix<double, 9, 3> C = Eigen::Matrix<double, 9, 3>::Zero();
  C.block<3, 3>(3, 0) = dR_ * dt;
  C.block<3, 3>(6, 0) = 0.5 * dR_ * dt2;
  const double gyro_var = noise_.gyro_noise_density * noise_.gyro_noise_density / dt;
  const double accel_var = noise_.accel_noise_density * noise_.accel_noise_density / dt;
  cov_ = A * cov_ * A.transpose() + gyro_var * B * B.transpose() + accel_var * C * C.transpose();

  // Bias Jacobians (appendix, Eq. 69-71); p first, it uses v's and R's old values.
  dp_dba_ += dv_dba_ * dt - 0.5 * dR_ * dt2;
  dp_dbg_ += dv_dbg_ * dt - 0.5 * dR_ * acc_skew * dR_dbg_ * dt2;
  dv_dba_ -= dR_ * dt;
  dv_dbg_ -= dR_ * acc_skew * dR_dbg_ * dt;
  dR_dbg_ = dR_step.transpose() * dR_dbg_ - Jr * dt;

  dp_ += dv_ * dt + 0.5 * acc_i * dt2;
  dv_ += acc_i * dt;
  dR_ = dR_next;
  dt_s_ += dt;
}

void Preintegration::integrateInterval(const std::vector<ImuMeasurement>& samples, double t_begin_s,
                                       double t_end_s) {
  if (samples.empty() || samples.front().t_s > t_begin_s + 1e-9 ||
      samples.back().t_s < t_end_s - 1e-9 || !(t_end_s > t_begin_s)) {
    throw InputError("Preintegration: IMU samples do not cover [" + std::to_string(t_begin_s) +
                     ", " + std::to_string(t_end_s) + "] s");
  }
  for (std::size_t k = 0; k + 1 < samples.size(); ++k) {
    const double t0 = std::max(samples[k].t_s, t_begin_s);
    const double t1 = std::min(samples[k + 1].t_s, t_end_s);
    if (t1 <= t0 + 1e-12) continue;
    integrate(interpolate(samples[k], samples[k + 1], t0),
              interpolate(samples[k], samples[k + 1], t1));
  }
}

void Preintegration::reintegrate(const ImuBias& bias) {
  bias_ = bias;
  reset();
  for (std::size_t k = 0; k + 1 < samples_.size(); k += 2) step(samples_[k], samples_[k + 1]);
}

Eigen::Matrix<double, 15, 15> Preintegration::factorCovariance() const {
  Eigen::Matrix<double, 15, 15> cov = Eigen::Matrix<double, 15, 15>::Zero();
  cov.topLeftCorner<9, 9>() = cov_;
  const double gyro_walk = noise_.gyro_random_walk * noise_.gyro_random_walk * dt_s_;
  const double accel_walk = noise_.accel_random_walk * noise_.accel_random_walk * dt_s_;
  cov.block<3, 3>(9, 9) = Eigen::Matrix3d::Identity() * gyro_walk;
  cov.block<3, 3>(12, 12) = Eigen::Matrix3d::Identity() * accel_walk;
  return cov;
}

Eigen::Matrix3d Preintegration::correctedDeltaR(const ImuBias& b) const {
  return dR_ * expSO3(dR_dbg_ * (b.gyro_rad_s - bias_.gyro_rad_s));
}

Eigen::Vector3d Preintegration::correctedDeltaV(const ImuBias& b) const {
  return dv_ + dv_dbg_ * (b.gyro_rad_s - bias_.gyro_rad_s) +
         dv_dba_ * (b.accel_mps2 - bias_.accel_mps2);
}

Eigen::Vector3d Preintegration::correctedDeltaP(const ImuBias& b) const {
  return dp_ + dp_dbg_ * (b.gyro_rad_s - bias_.gyro_rad_s) +
         dp_dba_ * (b.accel_mps2 - bias_.accel_mps2);
}

void Preintegration::predict(const Eigen::Matrix3d& R_W_Bi, const Eigen::Vector3d& p_W_Bi,
                             const Eigen::Vector3d& v_W_Bi, const ImuBias& b,
                             const Eigen::Vector3d& gravity_W, Eigen::Matrix3d* R_W_Bj,
                             Eigen::Vector3d* p_W_Bj, Eigen::Vector3d* v_W_Bj) const {
  const double t = dt_s_;
  *R_W_Bj = R_W_Bi * correctedDeltaR(b);
  *v_W_Bj = v_W_Bi + gravity_W * t + R_W_Bi * correctedDeltaV(b);
  *p_W_Bj = p_W_Bi + v_W_Bi * t + 0.5 * gravity_W * t * t + R_W_Bi * correctedDeltaP(b);
}

}  // namespace strata::odometry
