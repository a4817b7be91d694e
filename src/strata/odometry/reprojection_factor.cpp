#include "strata/odometry/reprojection_factor.h"

#include "strata/odometry/so3.h"

namespace strata::odometry {
namespace {

// d(R(q) v)/d(x, y, z, w) for a unit quaternion with R(q) v = v + 2w (u x v) + 2 u x (u x v).
Eigen::Matrix<double, 3, 4> rotateJacobian(const Eigen::Quaterniond& q, const Eigen::Vector3d& v) {
  const Eigen::Vector3d u = q.vec();
  Eigen::Matrix<double, 3, 4> J;
  J.leftCols<3>() = -2.0 * q.w() * skew(v) + 2.0 * (u.dot(v) * Eigen::Matrix3d::Identity() +
                                                    u * v.transpose() - 2.0 * v * u.transpose());
  J.col(3) = 2.0 * u.cross(v);
  return J;
}

// d(R(q)^T v)/d(x, y, z, w): the same with u -> -u.
Eigen::Matrix<double, 3, 4> inverseRotateJacobian(const Eigen::Quaterniond& q,
                                                  const Eigen::Vector3d& v) {
  const Eigen::Vector3d u = q.vec();
  Eigen::Matrix<double, 3, 4> J;
  J.leftCols<3>() = 2.0 * q.w() * skew(v) + 2.0 * (u.dot(v) * Eigen::Matrix3d::Identity() +
                                                   u * v.transpose() - 2.0 * v * u.transpose());
  J.col(3) = -2.0 * u.cross(v);
  return J;
}

}  // namespace

ReprojectionCost::ReprojectionCost(const Eigen::Vector3d& bearing_a,
                                   const Eigen::Isometry3d& T_B_Ca, const Eigen::Isometry3d& T_B_Cj,
                                   const PinholeIntrinsics& intrinsics_j,
                                   const Eigen::Vector2d& uv_j, double sigma_px)
    : ray_Ba_(T_B_Ca.linear() * bearing_a),
      t_B_Ca_(T_B_Ca.translation()),
      R_Cj_B_(T_B_Cj.linear().transpose()),
      t_Cj_B_(-(T_B_Cj.linear().transpose() * T_B_Cj.translation())),
      k_(intrinsics_j),
      uv_(uv_j),
      sigma_px_(sigma_px) {}

bool ReprojectionCost::Evaluate(double const* const* parameters, double* residuals,
                                double** jacobians) const {
  const Eigen::Map<const Eigen::Quaterniond> q_a(parameters[0]), q_j(parameters[1]);
  const Eigen::Map<const Eigen::Vector3d> p_a(parameters[0] + 4), p_j(parameters[1] + 4);
  const double rho = parameters[2][0];
  const Eigen::Vector3d p_Ba = ray_Ba_ / rho + t_B_Ca_;
  const Eigen::Matrix3d R_a = q_a.toRotationMatrix(), R_j = q_j.toRotationMatrix();
  const Eigen::Vector3d d = R_a * p_Ba + p_a - p_j;
  const Eigen::Vector3d p_C = R_Cj_B_ * (R_j.transpose() * d) + t_Cj_B_;
  if (!(p_C.z() > 1e-6)) return false;
  const double iz = 1.0 / p_C.z();
  residuals[0] = (k_.fx_px * p_C.x() * iz + k_.cx_px - uv_.x()) / sigma_px_;
  residuals[1] = (k_.fy_px * p_C.y() * iz + k_.cy_px - uv_.y()) / sigma_px_;
  if (!jacobians) return true;
  Eigen::Matrix<double, 2, 3> D;
  D << k_.fx_px * iz, 0.0, -k_.fx_px * p_C.x() * iz * iz, 0.0, k_.fy_px * iz,
      -k_.fy_px * p_C.y() * iz * iz;
  D /= sigma_px_;
  const Eigen::Matrix<double, 2, 3> D_B = D * R_Cj_B_;          // d r / d p_Bj
  const Eigen::Matrix<double, 2, 3> M = D_B * R_j.transpose();  // d r / d p_W
  using Row2x7 = Eigen::Matrix<double, 2, 7, Eigen::RowMajor>;
  if (jacobians[0]) {
    Eigen::Map<Row2x7> J(jacobians[0]);
    J.leftCols<4>() = M * rotateJacobian(q_a, p_Ba);
    J.rightCols<3>() = M;
  }
  if (jacobians[1]) {
    Eigen::Map<Row2x7> J(jacobians[1]);
    J.leftCols<4>() = D_B * inverseRotateJacobian(q_j, d);
    J.rightCols<3>() = -M;
  }
  if (jacobians[2]) {
    Eigen::Map<Eigen::Vector2d> J(jacobians[2]);
    J = M * R_a * (-ray_Ba_ / (rho * rho));
  }
  return true;
}

}  // namespace strata::odometry
