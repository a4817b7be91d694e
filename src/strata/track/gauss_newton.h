#pragma once
// The host half of the ICP (double): the 6x6 system from the reduced sums, its LDLT solve, its
// conditioning, and the pose update T_W_C <- T_W_C exp(ξ), ξ = (translation, rotation).
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "strata/track/normal_equations.h"

namespace strata {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// JᵀJ as a full symmetric matrix.
Matrix6d fullJtJ(const NormalEquations& sums);

struct GaussNewtonStep {
  bool solved = false;  // false when JᵀJ is not positive definite (or there are no inliers)
  Vector6d xi = Vector6d::Zero();    // minimiser of Σ w (r + J ξ)²: JᵀJ ξ = −Jᵀr
  double min_eigenvalue = 0.0;       // of JᵀJ / inliers
  int unconstrained_directions = 0;  // eigenvectors left out of the step (see below)
};

/// With min_eigenvalue > 0 and a system whose smallest eigenvalue of JᵀJ / inliers is below it,
/// the step is solved in the span of the eigenvectors at or above it only (the others get no
/// update): on a single plane the in-plane directions would otherwise take a step of rounding
/// noise, whose size depends on the device's float summation order.
GaussNewtonStep solveGaussNewton(const NormalEquations& sums, double min_eigenvalue = 0.0);

/// The covariance of ξ at a least-squares minimum: σ̂² (JᵀJ)⁻¹ with σ̂² = Σ r² / (rows − 6), the
/// Gauss-Newton (Laplace) estimate for independent residuals of equal variance. `rows` counts
/// every residual in the sums (point-to-plane and photometric). Residuals of neighbouring pixels
/// are correlated, so this understates the true spread (docs/track.md gives the measured ratio);
/// it is a comparison between frames and between directions, not a calibrated error bar.
/// Infinite on the diagonal when JᵀJ is not positive definite or rows ≤ 6.
Matrix6d poseCovariance(const NormalEquations& sums, double rows);

/// T exp(ξ) with the rotation exp(ω) (Rodrigues) and the translation ξ's first three entries
/// applied in the camera frame (a retraction; first-order equal to the SE(3) exponential).
Eigen::Isometry3d applyIncrement(const Eigen::Isometry3d& T_W_C, const Vector6d& xi);

/// Rotation angle of a pose, degrees.
double rotationAngleDeg(const Eigen::Isometry3d& T);

}  // namespace strata
