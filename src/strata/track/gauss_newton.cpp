#include "strata/track/gauss_newton.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

namespace strata {

Matrix6d fullJtJ(const NormalEquations& sums) {
  Matrix6d H;
  int k = 0;
  for (int i = 0; i < 6; ++i) {
    for (int j = i; j < 6; ++j) {
      H(i, j) = sums.JtJ[static_cast<std::size_t>(k++)];
      H(j, i) = H(i, j);
    }
  }
  return H;
}

GaussNewtonStep solveGaussNewton(const NormalEquations& sums, double min_eigenvalue) {
  GaussNewtonStep step;
  if (sums.inliers < 6) return step;
  const double n = static_cast<double>(sums.inliers);
  const Matrix6d H = fullJtJ(sums);
  Vector6d g;
  for (int i = 0; i < 6; ++i) g[i] = sums.Jtr[static_cast<std::size_t>(i)];
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eigen(H / n);
  if (eigen.info() != Eigen::Success) return step;
  step.min_eigenvalue = eigen.eigenvalues()[0];
  if (min_eigenvalue > 0.0 && step.min_eigenvalue < min_eigenvalue) {
    // Weakly constrained directions (a plane's in-plane translation, say) would take a step
    // made of rounding noise: solve only in the eigenvectors the data constrains.
    for (int i = 0; i < 6; ++i) {
      const double lambda = eigen.eigenvalues()[i];
      if (lambda < min_eigenvalue) {
        ++step.unconstrained_directions;
        continue;
      }
      const Vector6d v = eigen.eigenvectors().col(i);
      step.xi -= v * (v.dot(g) / (n * lambda));
    }
    step.solved = step.unconstrained_directions < 6 && step.xi.allFinite();
    return step;
  }
  const Eigen::LDLT<Matrix6d> ldlt(H);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || !(step.min_eigenvalue > 0.0)) {
    return step;
  }
  step.xi = ldlt.solve(-g);
  step.solved = step.xi.allFinite();
  return step;
}

Matrix6d poseCovariance(const NormalEquations& sums, double rows) {
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eigen(fullJtJ(sums));
  if (!(rows > 6.0) || eigen.info() != Eigen::Success || !(eigen.eigenvalues()[0] > 0.0)) {
    return Matrix6d::Identity() * std::numeric_limits<double>::infinity();
  }
  const double variance = sums.residual_sq / (rows - 6.0);
  return variance * eigen.eigenvectors() * eigen.eigenvalues().cwiseInverse().asDiagonal() *
         eigen.eigenvectors().transpose();
}

Eigen::Isometry3d applyIncrement(const Eigen::Isometry3d& T_W_C, const Vector6d& xi) {
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d omega = xi.tail<3>();
  const double angle = omega.norm();
  if (angle > 0.0) delta.linear() = Eigen::AngleAxisd(angle, omega / angle).toRotationMatrix();
  delta.translation() = xi.head<3>();
  Eigen::Isometry3d out = T_W_C * delta;
  // Keep the rotation orthonormal over many updates.
  out.linear() = Eigen::Quaterniond(out.rotation()).normalized().toRotationMatrix();
  return out;
}

double rotationAngleDeg(const Eigen::Isometry3d& T) {
  return Eigen::AngleAxisd(T.rotation()).angle() * 180.0 / M_PI;
}

}  // namespace strata
