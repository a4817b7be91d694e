#pragma once
// SO(3) helpers for the IMU preintegration (Forster et al., TRO 2017, Sec. III): exp, log, skew
// and the right Jacobian. Double precision; the Ceres factors use ceres/rotation.h for Jets.
#include <Eigen/Core>

namespace strata::odometry {

Eigen::Matrix3d skew(const Eigen::Vector3d& w);
/// Rodrigues' formula; exact near zero (second-order series below 1e-8 rad).
Eigen::Matrix3d expSO3(const Eigen::Vector3d& phi);
/// Rotation vector of R with angle in [0, pi].
Eigen::Vector3d logSO3(const Eigen::Matrix3d& R);
/// J_r(phi), Eq. (8): Exp(phi + dphi) ~ Exp(phi) Exp(J_r(phi) dphi).
Eigen::Matrix3d rightJacobianSO3(const Eigen::Vector3d& phi);

}  // namespace strata::odometry
