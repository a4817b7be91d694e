#pragma once
// Reprojection residuals of a landmark stored as inverse depth rho (1/m) along the ray of its
// first observation in the left camera of its anchor keyframe a: p_Ca = bearing_a / rho with
// bearing_a = (x, y, 1). Residual: (projected - observed) / sigma_px, 2 values, under the robust
// loss the estimator chooses. ReprojectionCost has analytic Jacobians (the estimator's, several
// times faster); ReprojectionFactor is the same residual for ceres::AutoDiff, kept as the
// reference the tests compare the analytic Jacobians with.
#include <ceres/autodiff_cost_function.h>
#include <ceres/sized_cost_function.h>

#include <Eigen/Geometry>

#include "strata/odometry/camera_rig.h"
#include "strata/odometry/state_parameters.h"

namespace strata::odometry {

namespace internal {
template <typename T>
bool projectResidual(const PinholeIntrinsics& k, const Eigen::Matrix<T, 3, 1>& p_C,
                     const Eigen::Vector2d& uv, double sigma_px, T* residual) {
  if (!(p_C.z() > T(1e-6))) return false;  // behind the camera: step rejected
  residual[0] = (T(k.fx_px) * p_C.x() / p_C.z() + T(k.cx_px) - T(uv.x())) / T(sigma_px);
  residual[1] = (T(k.fy_px) * p_C.y() / p_C.z() + T(k.cy_px) - T(uv.y())) / T(sigma_px);
  return true;
}
}  // namespace internal

/// Observation in keyframe j != a (left or right camera of j). Blocks: pose_a[7], pose_j[7],
/// rho[1].
class ReprojectionFactor {
 public:
  ReprojectionFactor(const Eigen::Vector3d& bearing_a, const Eigen::Isometry3d& T_B_Ca,
                     const Eigen::Isometry3d& T_B_Cj, const PinholeIntrinsics& intrinsics_j,
                     const Eigen::Vector2d& uv_j, double sigma_px)
      : bearing_a_(bearing_a),
        T_B_Ca_(T_B_Ca),
        T_Cj_B_(T_B_Cj.inverse()),
        k_(intrinsics_j),
        uv_(uv_j),
        sigma_px_(sigma_px) {}

  template <typename T>
  bool operator()(const T* pose_a, const T* pose_j, const T* rho, T* residual) const {
    using Vec3 = Eigen::Matrix<T, 3, 1>;
    const Eigen::Map<const Eigen::Quaternion<T>> q_a(pose_a), q_j(pose_j);
    const Eigen::Map<const Vec3> p_a(pose_a + 4), p_j(pose_j + 4);
    const Vec3 p_Ca = bearing_a_.cast<T>() / rho[0];
    const Vec3 p_Ba = T_B_Ca_.linear().cast<T>() * p_Ca + T_B_Ca_.translation().cast<T>();
    const Vec3 p_W = q_a * p_Ba + p_a;
    const Vec3 p_Bj = q_j.conjugate() * (p_W - p_j);
    const Vec3 p_Cj = T_Cj_B_.linear().cast<T>() * p_Bj + T_Cj_B_.translation().cast<T>();
    return internal::projectResidual(k_, p_Cj, uv_, sigma_px_, residual);
  }

  static ceres::CostFunction* create(const Eigen::Vector3d& bearing_a,
                                     const Eigen::Isometry3d& T_B_Ca,
                                     const Eigen::Isometry3d& T_B_Cj,
                                     const PinholeIntrinsics& intrinsics_j,
                                     const Eigen::Vector2d& uv_j, double sigma_px) {
    return new ceres::AutoDiffCostFunction<ReprojectionFactor, 2, kPoseSize, kPoseSize, 1>(
        new ReprojectionFactor(bearing_a, T_B_Ca, T_B_Cj, intrinsics_j, uv_j, sigma_px));
  }

 private:
  Eigen::Vector3d bearing_a_;
  Eigen::Isometry3d T_B_Ca_, T_Cj_B_;
  PinholeIntrinsics k_;
  Eigen::Vector2d uv_;
  double sigma_px_;
};

/// ReprojectionFactor's residual with analytic Jacobians (ambient: quaternion x, y, z, w and
/// position per pose block, so Ceres' manifold product applies as for autodiff).
class ReprojectionCost final : public ceres::SizedCostFunction<2, kPoseSize, kPoseSize, 1> {
 public:
  ReprojectionCost(const Eigen::Vector3d& bearing_a, const Eigen::Isometry3d& T_B_Ca,
                   const Eigen::Isometry3d& T_B_Cj, const PinholeIntrinsics& intrinsics_j,
                   const Eigen::Vector2d& uv_j, double sigma_px);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Eigen::Vector3d ray_Ba_;  // R_B_Ca bearing_a
  Eigen::Vector3d t_B_Ca_;
  Eigen::Matrix3d R_Cj_B_;
  Eigen::Vector3d t_Cj_B_;
  PinholeIntrinsics k_;
  Eigen::Vector2d uv_;
  double sigma_px_;
};

/// The right-camera observation in the anchor keyframe itself: depends on rho only (the stereo
/// baseline fixes the scale). Block: rho[1].
class AnchorStereoFactor {
 public:
  AnchorStereoFactor(const Eigen::Vector3d& bearing_a, const Eigen::Isometry3d& T_Cr_Cl,
                     const PinholeIntrinsics& right, const Eigen::Vector2d& uv_right,
                     double sigma_px)
      : bearing_a_(bearing_a), T_Cr_Cl_(T_Cr_Cl), k_(right), uv_(uv_right), sigma_px_(sigma_px) {}

  template <typename T>
  bool operator()(const T* rho, T* residual) const {
    using Vec3 = Eigen::Matrix<T, 3, 1>;
    const Vec3 p_Cl = bearing_a_.cast<T>() / rho[0];
    const Vec3 p_Cr = T_Cr_Cl_.linear().cast<T>() * p_Cl + T_Cr_Cl_.translation().cast<T>();
    return internal::projectResidual(k_, p_Cr, uv_, sigma_px_, residual);
  }

  static ceres::CostFunction* create(const Eigen::Vector3d& bearing_a,
                                     const Eigen::Isometry3d& T_Cr_Cl,
                                     const PinholeIntrinsics& right,
                                     const Eigen::Vector2d& uv_right, double sigma_px) {
    return new ceres::AutoDiffCostFunction<AnchorStereoFactor, 2, 1>(
        new AnchorStereoFactor(bearing_a, T_Cr_Cl, right, uv_right, sigma_px));
  }

 private:
  Eigen::Vector3d bearing_a_;
  Eigen::Isometry3d T_Cr_Cl_;
  PinholeIntrinsics k_;
  Eigen::Vector2d uv_;
  double sigma_px_;
};

}  // namespace strata::odometry
