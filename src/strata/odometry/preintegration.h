#pragma once
// IMU preintegration on the manifold between two keyframes i and j (Forster, Carlone, Dellaert,
// Scaramuzza, "On-Manifold Preintegration for Real-Time Visual-Inertial Odometry", TRO 2017):
// the relative motion increments dR, dv, dp in the body frame of i, their 9x9 covariance, and the
// first-order Jacobians with respect to the bias used to integrate, so a small bias update
// corrects the increments without re-integration (Eq. 44).
//
// Integration: midpoint. Each step between samples k and k+1 rotates by the mean of their
// (bias-corrected) rates and accelerates by the mean of their accelerations rotated into frame i
// at both ends. Covariance and bias Jacobians follow the Euler-form recursions of the paper's
// appendix with those mean rates (first order; the difference is O(dt) of a small term).
//
// Convention: dR = R_i^T R_j, dv = R_i^T (v_j - v_i - g dt), dp = R_i^T (p_j - p_i - v_i dt -
// g dt^2 / 2) with B the IMU frame and W the world frame (Eq. 33). Noise of the increments
// (Eq. 38-41): dR_measured = dR Exp(dphi), dv_measured = dv + ddv, dp_measured = dp + ddp; the
// covariance is that of [dphi, ddv, ddp].
#include <Eigen/Core>
#include <vector>

#include "strata/odometry/imu_types.h"

namespace strata::odometry {

/// Not thread safe; a value type (copyable).
class Preintegration {
 public:
  /// bias: the estimate the increments are integrated with (the linearisation point).
  Preintegration(const ImuBias& bias, const ImuNoise& noise);

  /// Integrates from a.t_s to b.t_s (b.t_s > a.t_s) with the midpoint rule. Throws InputError for
  /// a non-positive time step or non-finite samples.
  void integrate(const ImuMeasurement& a, const ImuMeasurement& b);
  /// Integrates samples[0..n-1] over [t_begin, t_end], interpolating linearly at both ends.
  /// Throws InputError when the samples do not cover the interval.
  void integrateInterval(const std::vector<ImuMeasurement>& samples, double t_begin_s,
                         double t_end_s);
  /// Starts over from the stored samples with a new linearisation bias (the correction of Eq. 44
  /// is only first order; re-integrate when the bias moves far).
  void reintegrate(const ImuBias& bias);

  double dt_s() const { return dt_s_; }
  const ImuBias& bias() const { return bias_; }
  const Eigen::Matrix3d& deltaR() const { return dR_; }
  const Eigen::Vector3d& deltaV() const { return dv_; }
  const Eigen::Vector3d& deltaP() const { return dp_; }
  /// Covariance of [dphi, dv, dp] from the white noise (Eq. 62 -> 63).
  const Eigen::Matrix<double, 9, 9>& covariance() const { return cov_; }
  /// 15x15 covariance of the IMU factor's residual [dphi, dv, dp, dbg, dba]: the 9x9 block above
  /// plus the bias random walk over dt (sigma_b^2 dt).
  Eigen::Matrix<double, 15, 15> factorCovariance() const;

  const Eigen::Matrix3d& dR_dbg() const { return dR_dbg_; }
  const Eigen::Matrix3d& dv_dbg() const { return dv_dbg_; }
  const Eigen::Matrix3d& dv_dba() const { return dv_dba_; }
  const Eigen::Matrix3d& dp_dbg() const { return dp_dbg_; }
  const Eigen::Matrix3d& dp_dba() const { return dp_dba_; }

  /// First-order bias-corrected increments for bias `b` (Eq. 44).
  Eigen::Matrix3d correctedDeltaR(const ImuBias& b) const;
  Eigen::Vector3d correctedDeltaV(const ImuBias& b) const;
  Eigen::Vector3d correctedDeltaP(const ImuBias& b) const;

  /// Predicted state at j from state at i (Eq. 33 solved for j), with the first-order correction
  /// for bias `b`. gravity_W: e.g. (0, 0, -9.81).
  void predict(const Eigen::Matrix3d& R_W_Bi, const Eigen::Vector3d& p_W_Bi,
               const Eigen::Vector3d& v_W_Bi, const ImuBias& b, const Eigen::Vector3d& gravity_W,
               Eigen::Matrix3d* R_W_Bj, Eigen::Vector3d* p_W_Bj, Eigen::Vector3d* v_W_Bj) const;

 private:
  void reset();
  void step(const ImuMeasurement& a, const ImuMeasurement& b);

  ImuBias bias_;
  ImuNoise noise_;
  std::vector<ImuMeasurement> samples_;  // pairs (a, b) of every step, kept for re-integration
  double dt_s_ = 0.0;
  Eigen::Matrix3d dR_;
  Eigen::Vector3d dv_, dp_;
  Eigen::Matrix<double, 9, 9> cov_;
  Eigen::Matrix3d dR_dbg_, dv_dbg_, dv_dba_, dp_dbg_, dp_dba_;
};

/// Linear interpolation of two samples at t_s (a.t_s <= t_s <= b.t_s).
ImuMeasurement interpolate(const ImuMeasurement& a, const ImuMeasurement& b, double t_s);

}  // namespace strata::odometry
