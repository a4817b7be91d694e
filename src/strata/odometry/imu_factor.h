#pragma once
// The IMU factor between consecutive keyframes i and j (Forster et al., TRO 2017, Eq. 45 plus
// the bias random walk): 15 residuals [r_dR, r_dv, r_dp, r_bg, r_ba], whitened by the square root
// of the inverse factor covariance. Parameter blocks: pose_i[7], speed_bias_i[9], pose_j[7],
// speed_bias_j[9] (state_parameters.h). Jacobians by ceres::AutoDiff: slower than analytic ones
// but free of derivation errors, and the window is small.
#include <ceres/autodiff_cost_function.h>
#include <ceres/rotation.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <memory>

#include "strata/odometry/preintegration.h"
#include "strata/odometry/state_parameters.h"

namespace strata::odometry {

class ImuFactor {
 public:
  /// Keeps a shared reference: the estimator may re-integrate (change the linearisation bias)
  /// only between solves, and must then make a new factor.
  ImuFactor(std::shared_ptr<const Preintegration> preintegration, const Eigen::Vector3d& gravity_W)
      : pre_(std::move(preintegration)), gravity_W_(gravity_W) {
    Eigen::Matrix<double, 15, 15> cov = pre_->factorCovariance();
    // A floor far below any real noise keeps the information finite for noise-free configs.
    cov.diagonal().array() += 1e-15;
    // sqrt_information^T sqrt_information = cov^-1 (lower Cholesky of the information).
    const Eigen::Matrix<double, 15, 15> information = cov.inverse().selfadjointView<Eigen::Upper>();
    sqrt_information_ = Eigen::LLT<Eigen::Matrix<double, 15, 15>>(information).matrixU();
  }

  template <typename T>
  bool operator()(const T* pose_i, const T* sb_i, const T* pose_j, const T* sb_j,
                  T* residual) const {
    using Vec3 = Eigen::Matrix<T, 3, 1>;
    using Quat = Eigen::Quaternion<T>;
    const Eigen::Map<const Quat> q_i(pose_i), q_j(pose_j);
    const Eigen::Map<const Vec3> p_i(pose_i + 4), p_j(pose_j + 4);
    const Eigen::Map<const Vec3> v_i(sb_i), bg_i(sb_i + 3), ba_i(sb_i + 6);
    const Eigen::Map<const Vec3> v_j(sb_j), bg_j(sb_j + 3), ba_j(sb_j + 6);
    const ImuBias& b0 = pre_->bias();
    const Vec3 dbg = bg_i - b0.gyro_rad_s.cast<T>();
    const Vec3 dba = ba_i - b0.accel_mps2.cast<T>();

    // Eq. (44): first-order bias correction of the increments.
    const Vec3 phi = pre_->dR_dbg().cast<T>() * dbg;
    T q_corr_wxyz[4];
    ceres::AngleAxisToQuaternion(phi.data(), q_corr_wxyz);
    const Quat q_corr(q_corr_wxyz[0], q_corr_wxyz[1], q_corr_wxyz[2], q_corr_wxyz[3]);
    const Quat dq = Quat(Eigen::Quaterniond(pre_->deltaR()).cast<T>()) * q_corr;
    const Vec3 dv =
        pre_->deltaV().cast<T>() + pre_->dv_dbg().cast<T>() * dbg + pre_->dv_dba().cast<T>() * dba;
    const Vec3 dp =
        pre_->deltaP().cast<T>() + pre_->dp_dbg().cast<T>() * dbg + pre_->dp_dba().cast<T>() * dba;

    const T dt = T(pre_->dt_s());
    const Vec3 g = gravity_W_.cast<T>();
    const Quat q_i_inv = q_i.conjugate();
    // r_dR = Log(dR^T R_i^T R_j), through the quaternion (ceres handles the small-angle limit).
    const Quat q_err = dq.conjugate() * q_i_inv * q_j;
    const T q_err_wxyz[4] = {q_err.w(), q_err.x(), q_err.y(), q_err.z()};
    Eigen::Matrix<T, 15, 1> r;
    ceres::QuaternionToAngleAxis(q_err_wxyz, r.data());
    r.template segment<3>(3) = q_i_inv * (v_j - v_i - g * dt) - dv;
    r.template segment<3>(6) = q_i_inv * (p_j - p_i - v_i * dt - T(0.5) * g * dt * dt) - dp;
    r.template segment<3>(9) = bg_j - bg_i;
    r.template segment<3>(12) = ba_j - ba_i;
    Eigen::Map<Eigen::Matrix<T, 15, 1>> out(residual);
    out = sqrt_information_.cast<T>() * r;
    return true;
  }

  static ceres::CostFunction* create(std::shared_ptr<const Preintegration> preintegration,
                                     const Eigen::Vector3d& gravity_W) {
    return new ceres::AutoDiffCostFunction<ImuFactor, 15, kPoseSize, kSpeedBiasSize, kPoseSize,
                                           kSpeedBiasSize>(
        new ImuFactor(std::move(preintegration), gravity_W));
  }

 private:
  std::shared_ptr<const Preintegration> pre_;
  Eigen::Vector3d gravity_W_;
  Eigen::Matrix<double, 15, 15> sqrt_information_;
};

}  // namespace strata::odometry
