#include "strata/odometry/initialization.h"

#include <Eigen/Dense>
#include <cmath>

#include "strata/core/error.h"
#include "strata/odometry/so3.h"

namespace strata::odometry {

Eigen::Matrix3d rotationBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return Eigen::Quaterniond::FromTwoVectors(a, b).toRotationMatrix();
}

namespace {

struct WindowStats {
  int count = 0;
  double span_s = 0.0;
  Eigen::Vector3d mean_w = Eigen::Vector3d::Zero(), mean_a = Eigen::Vector3d::Zero();
  Eigen::Vector3d std_w = Eigen::Vector3d::Zero(), std_a = Eigen::Vector3d::Zero();
};

WindowStats windowStats(const std::vector<ImuMeasurement>& samples, double t_end_s,
                        double window_s) {
  WindowStats w;
  Eigen::Vector3d sq_w = Eigen::Vector3d::Zero(), sq_a = Eigen::Vector3d::Zero();
  double t_min = t_end_s, t_max = t_end_s;
  for (const ImuMeasurement& m : samples) {
    if (m.t_s < t_end_s - window_s - 1e-9 || m.t_s > t_end_s + 1e-9) continue;
    w.mean_w += m.gyro_rad_s;
    w.mean_a += m.accel_mps2;
    sq_w += m.gyro_rad_s.cwiseAbs2();
    sq_a += m.accel_mps2.cwiseAbs2();
    t_min = std::min(t_min, m.t_s);
    t_max = w.count == 0 ? m.t_s : std::max(t_max, m.t_s);
    ++w.count;
  }
  if (w.count == 0) return w;
  w.span_s = t_max - t_min;
  w.mean_w /= w.count;
  w.mean_a /= w.count;
  w.std_w = (sq_w / w.count - w.mean_w.cwiseAbs2()).cwiseMax(0.0).cwiseSqrt();
  w.std_a = (sq_a / w.count - w.mean_a.cwiseAbs2()).cwiseMax(0.0).cwiseSqrt();
  return w;
}

}  // namespace

ImuMotion classifyMotion(const std::vector<ImuMeasurement>& samples, double t_end_s,
                         const StandstillConfig& config) {
  const WindowStats w = windowStats(samples, t_end_s, config.window_s);
  if (w.count < 10 || w.span_s < 0.9 * config.window_s) return ImuMotion::kTooFewSamples;
  const bool still = w.std_w.maxCoeff() <= config.max_gyro_stddev_rad_s &&
                     w.std_a.maxCoeff() <= config.max_accel_stddev_mps2;
  return still ? ImuMotion::kStill : ImuMotion::kMoving;
}

std::optional<InitialState> initializeFromStandstill(const std::vector<ImuMeasurement>& samples,
                                                     double t_end_s,
                                                     const StandstillConfig& config) {
  if (classifyMotion(samples, t_end_s, config) != ImuMotion::kStill) return std::nullopt;
  const WindowStats w = windowStats(samples, t_end_s, config.window_s);
  if (w.mean_a.norm() < 1e-3) return std::nullopt;
  InitialState state;
  // At rest f_B = R_W_B^T (0 - g_W) = |g| R_W_B^T e_z.
  state.R_W_B = rotationBetween(w.mean_a.normalized(), Eigen::Vector3d::UnitZ());
  state.bias.gyro_rad_s = w.mean_w;
  return state;
}

namespace {

// Linear least squares on Log(dR_ij^T R_i^T R_j) = dR/dbg dbg, twice (re-integrating between).
bool estimateGyroBias(const std::vector<Eigen::Isometry3d>& T_V_B, std::vector<Preintegration>* pre,
                      Eigen::Vector3d* bias) {
  for (int iteration = 0; iteration < 2; ++iteration) {
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < pre->size(); ++i) {
      const Preintegration& p = (*pre)[i];
      const Eigen::Matrix3d R_ij = T_V_B[i].linear().transpose() * T_V_B[i + 1].linear();
      const Eigen::Vector3d r = logSO3(p.deltaR().transpose() * R_ij);
      A += p.dR_dbg().transpose() * p.dR_dbg();
      b += p.dR_dbg().transpose() * r;
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(A);
    if (!(eig.eigenvalues().minCoeff() > 1e-9)) return false;
    *bias += A.ldlt().solve(b);
    for (Preintegration& p : *pre) {
      ImuBias updated = p.bias();
      updated.gyro_rad_s = *bias;
      p.reintegrate(updated);
    }
  }
  return true;
}

// Rows of p_j - p_i = v_i dt + g dt^2/2 + R_i dp and v_j - v_i = g dt + R_i dv for unknowns
// [v_0 .. v_{n-1}, g] (g_basis maps the gravity unknowns; g_fixed is the known part).
void velocityGravitySystem(const std::vector<Eigen::Isometry3d>& T_V_B,
                           const std::vector<Preintegration>& pre, const Eigen::MatrixXd& g_basis,
                           const Eigen::Vector3d& g_fixed, Eigen::MatrixXd* A, Eigen::VectorXd* b) {
  const int n = static_cast<int>(T_V_B.size());
  const int ng = static_cast<int>(g_basis.cols());
  *A = Eigen::MatrixXd::Zero(6 * (n - 1), 3 * n + ng);
  *b = Eigen::VectorXd::Zero(6 * (n - 1));
  for (int i = 0; i + 1 < n; ++i) {
    const Preintegration& p = pre[static_cast<std::size_t>(i)];
    const double dt = p.dt_s();
    const Eigen::Matrix3d R_i = T_V_B[static_cast<std::size_t>(i)].linear();
    const Eigen::Vector3d dpos = T_V_B[static_cast<std::size_t>(i) + 1].translation() -
                                 T_V_B[static_cast<std::size_t>(i)].translation();
    const int r = 6 * i;
    A->block<3, 3>(r, 3 * i) = Eigen::Matrix3d::Identity() * dt;
    A->block(r, 3 * n, 3, ng) = 0.5 * dt * dt * g_basis;
    b->segment<3>(r) = dpos - R_i * p.deltaP() - 0.5 * dt * dt * g_fixed;
    A->block<3, 3>(r + 3, 3 * i) = -Eigen::Matrix3d::Identity();
    A->block<3, 3>(r + 3, 3 * i + 3) = Eigen::Matrix3d::Identity();
    A->block(r + 3, 3 * n, 3, ng) = -dt * g_basis;
    b->segment<3>(r + 3) = R_i * p.deltaV() + dt * g_fixed;
  }
}

}  // namespace

std::optional<AlignmentResult> alignVisualInertial(const std::vector<Eigen::Isometry3d>& T_V_B,
                                                   std::vector<Preintegration>* preintegrations,
                                                   double gravity_mps2) {
  if (T_V_B.size() < 3 || preintegrations->size() + 1 != T_V_B.size()) {
    throw InputError("alignVisualInertial: needs n >= 3 poses and n - 1 preintegrations");
  }
  AlignmentResult result;
  result.gyro_bias = preintegrations->front().bias().gyro_rad_s;
  if (!estimateGyroBias(T_V_B, preintegrations, &result.gyro_bias)) return std::nullopt;

  const int n = static_cast<int>(T_V_B.size());
  Eigen::MatrixXd A;
  Eigen::VectorXd b;
  velocityGravitySystem(T_V_B, *preintegrations, Eigen::Matrix3d::Identity(),
                        Eigen::Vector3d::Zero(), &A, &b);
  Eigen::VectorXd x = A.colPivHouseholderQr().solve(b);
  Eigen::Vector3d g = x.tail<3>();
  if (!g.allFinite() || std::abs(g.norm() - gravity_mps2) > 0.1 * gravity_mps2) {
    return std::nullopt;
  }
  // Refine on the sphere |g| = gravity_mps2: two tangent unknowns per iteration.
  for (int iteration = 0; iteration < 4; ++iteration) {
    const Eigen::Vector3d g0 = gravity_mps2 * g.normalized();
    Eigen::Matrix<double, 3, 2> basis;
    const Eigen::Vector3d axis =
        std::abs(g0.normalized().x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    basis.col(0) = g0.cross(axis).normalized();
    basis.col(1) = g0.normalized().cross(basis.col(0));
    velocityGravitySystem(T_V_B, *preintegrations, basis, g0, &A, &b);
    x = A.colPivHouseholderQr().solve(b);
    g = g0 + basis * x.tail<2>();
  }
  result.gravity_V = gravity_mps2 * g.normalized();
  result.R_W_V = rotationBetween(result.gravity_V.normalized(), -Eigen::Vector3d::UnitZ());
  for (int i = 0; i < n; ++i) result.v_V_B.push_back(x.segment<3>(3 * i));
  return result;
}

}  // namespace strata::odometry
