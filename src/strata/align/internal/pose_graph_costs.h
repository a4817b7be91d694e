#pragma once
// Ceres residuals of the pose graph. A pose is two parameter blocks: position p_W_C[3] and the
// Eigen quaternion q_W_C[4] (x y z w, EigenQuaternionManifold).
// Edge error (decoupled, not the full SE(3) log): with the estimate T_ij = T_W_Ci^-1 * T_W_Cj and
// the measurement T_m, E = T_m^-1 * T_ij and e = (t(E), Log(R(E))), i.e. (tx ty tz rx ry rz) of a
// right perturbation T_ij = T_m * Exp(e) to first order, the order of the information matrices.
// NOTE: decoupled because it is exact for the rotation, needs no SE(3) left Jacobian, and for
// edges of a few metres and a few degrees differs from the SE(3) log only at second order.
// Residual: sqrt_information * e, sqrt_information = L^T with information = L * L^T.
// Internal to strata::align.
#include <ceres/autodiff_cost_function.h>
#include <ceres/rotation.h>

#include <Eigen/Geometry>
#include <cmath>

#include "strata/store/store_types.h"

namespace strata::align::internal {

using Vector6 = Eigen::Matrix<double, 6, 1>;

template <typename T>
Eigen::Matrix<T, 6, 1> edgeError(const T* p_i, const T* q_i, const T* p_j, const T* q_j,
                                 const Eigen::Vector3d& t_m, const Eigen::Quaterniond& q_m) {
  using Vec3 = Eigen::Matrix<T, 3, 1>;
  using Quat = Eigen::Quaternion<T>;
  const Eigen::Map<const Vec3> pi(p_i), pj(p_j);
  const Eigen::Map<const Quat> qi(q_i), qj(q_j);
  const Quat qi_inv = qi.conjugate();
  const Vec3 t_ij = qi_inv * (pj - pi);
  const Quat q_m_inv = q_m.conjugate().template cast<T>();
  const Quat q_e = q_m_inv * (qi_inv * qj);
  Eigen::Matrix<T, 6, 1> e;
  e.template head<3>() = q_m_inv * (t_ij - t_m.cast<T>());
  const T q_e_wxyz[4] = {q_e.w(), q_e.x(), q_e.y(), q_e.z()};
  ceres::QuaternionToAngleAxis(q_e_wxyz, e.data() + 3);
  return e;
}

/// Odometry (or any unswitched) edge between poses i and j.
struct EdgeCost {
  EdgeCost(const Eigen::Isometry3d& T_i_j, const store::Matrix6d& sqrt_information)
      : t_m(T_i_j.translation()), q_m(T_i_j.linear()), sqrt_info(sqrt_information) {}

  template <typename T>
  bool operator()(const T* p_i, const T* q_i, const T* p_j, const T* q_j, T* residual) const {
    Eigen::Map<Eigen::Matrix<T, 6, 1>> r(residual);
    r = sqrt_info.cast<T>() * edgeError(p_i, q_i, p_j, q_j, t_m, q_m);
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Isometry3d& T_i_j,
                                     const store::Matrix6d& sqrt_information) {
    return new ceres::AutoDiffCostFunction<EdgeCost, 6, 3, 4, 3, 4>(
        new EdgeCost(T_i_j, sqrt_information));
  }

  Eigen::Vector3d t_m;
  Eigen::Quaterniond q_m;
  store::Matrix6d sqrt_info;
};

/// Loop edge scaled by its switch s in [0, 1] (Sünderhauf & Protzel 2012).
struct SwitchedEdgeCost {
  SwitchedEdgeCost(const Eigen::Isometry3d& T_a_b, const store::Matrix6d& sqrt_information)
      : edge(T_a_b, sqrt_information) {}

  template <typename T>
  bool operator()(const T* p_a, const T* q_a, const T* p_b, const T* q_b, const T* s,
                  T* residual) const {
    edge(p_a, q_a, p_b, q_b, residual);
    for (int k = 0; k < 6; ++k) residual[k] *= s[0];
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Isometry3d& T_a_b,
                                     const store::Matrix6d& sqrt_information) {
    return new ceres::AutoDiffCostFunction<SwitchedEdgeCost, 6, 3, 4, 3, 4, 1>(
        new SwitchedEdgeCost(T_a_b, sqrt_information));
  }

  EdgeCost edge;
};

/// Prior pulling a switch to 1: sqrt(weight) * (1 - s).
struct SwitchPriorCost {
  explicit SwitchPriorCost(double weight) : sqrt_weight(std::sqrt(weight)) {}

  template <typename T>
  bool operator()(const T* s, T* residual) const {
    residual[0] = T(sqrt_weight) * (T(1.0) - s[0]);
    return true;
  }

  static ceres::CostFunction* create(double weight) {
    return new ceres::AutoDiffCostFunction<SwitchPriorCost, 1, 1>(new SwitchPriorCost(weight));
  }

  double sqrt_weight;
};

}  // namespace strata::align::internal
