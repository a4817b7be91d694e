#include "strata/odometry/so3.h"

#include <Eigen/Geometry>
#include <cmath>

namespace strata::odometry {

Eigen::Matrix3d skew(const Eigen::Vector3d& w) {
  Eigen::Matrix3d S;
  S << 0.0, -w.z(), w.y(), w.z(), 0.0, -w.x(), -w.y(), w.x(), 0.0;
  return S;
}

Eigen::Matrix3d expSO3(const Eigen::Vector3d& phi) {
  const double angle = phi.norm();
  if (angle < 1e-8) return Eigen::Matrix3d::Identity() + skew(phi) + 0.5 * skew(phi) * skew(phi);
  return Eigen::AngleAxisd(angle, phi / angle).toRotationMatrix();
}

Eigen::Vector3d logSO3(const Eigen::Matrix3d& R) {
  // Through the quaternion: stable near 0 and near pi, unlike acos of the trace.
  Eigen::Quaterniond q(R);
  q.normalize();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();
  const double s = q.vec().norm();
  if (s < 1e-10) return 2.0 * q.vec() / q.w();
  return 2.0 * std::atan2(s, q.w()) * q.vec() / s;
}

Eigen::Matrix3d rightJacobianSO3(const Eigen::Vector3d& phi) {
  const double angle = phi.norm();
  const Eigen::Matrix3d S = skew(phi);
  if (angle < 1e-5) return Eigen::Matrix3d::Identity() - 0.5 * S + S * S / 6.0;
  const double a2 = angle * angle;
  return Eigen::Matrix3d::Identity() - (1.0 - std::cos(angle)) / a2 * S +
         (angle - std::sin(angle)) / (a2 * angle) * S * S;
}

}  // namespace strata::odometry
