#pragma once
// Uniform quintic B-spline through points (C4: position, velocity, acceleration, jerk and snap are
// continuous), so simulated IMU signals are smooth and integrate back to the path.
#include <Eigen/Core>
#include <vector>

namespace strata::sim {

/// Thread safety: const methods may be called from several threads at once.
class QuinticBSpline {
 public:
  /// Interpolates points[k] at time k * segment_duration_s, starting and ending at rest (zero
  /// velocity and acceleration at both ends). Throws InputError for fewer than 2 points, a
  /// non-finite point or a non-positive duration.
  QuinticBSpline(const std::vector<Eigen::Vector3d>& points, double segment_duration_s);

  double duration_s() const { return segment_duration_s_ * segment_count_; }
  /// The `derivative`-th time derivative (0..5) at t. Outside [0, duration] the end segments'
  /// polynomials extrapolate smoothly.
  Eigen::Vector3d evaluate(double t_s, int derivative = 0) const;

  /// Uniform degree-5 B-spline basis matrix: p(u) = sum_m sum_j M(m, j) u^m c_j, u in [0, 1].
  static const Eigen::Matrix<double, 6, 6>& basisMatrix();

 private:
  double segment_duration_s_;
  int segment_count_;
  std::vector<Eigen::Vector3d> control_points_;  // segment_count_ + 5
};

}  // namespace strata::sim
