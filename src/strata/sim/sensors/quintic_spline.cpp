#include "strata/sim/sensors/quintic_spline.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <string>

#include "strata/core/error.h"

namespace strata::sim {
namespace {

constexpr int kDegree = 5;

double binomial(int n, int k) {
  double result = 1.0;
  for (int i = 1; i <= k; ++i) result = result * (n - k + i) / i;
  return result;
}

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

// Qin, "General matrix representations for B-splines", The Visual Computer 16, 2000:
// M(i, j) = C(d, d - i) / d! * sum_{s=j}^{d} (-1)^(s-j) C(d+1, s-j) (d - s)^(d-i), row i <-> u^i.
Eigen::Matrix<double, 6, 6> makeBasis() {
  Eigen::Matrix<double, 6, 6> M;
  for (int i = 0; i <= kDegree; ++i) {
    for (int j = 0; j <= kDegree; ++j) {
      double sum = 0.0;
      for (int s = j; s <= kDegree; ++s) {
        const double sign = ((s - j) % 2 == 0) ? 1.0 : -1.0;
        sum += sign * binomial(kDegree + 1, s - j) * std::pow(kDegree - s, kDegree - i);
      }
      M(i, j) = binomial(kDegree, kDegree - i) / factorial(kDegree) * sum;
    }
  }
  return M;
}

// Weights of the 6 control points for the n-th u-derivative at u: row vector of d^n/du^n [u^m] M.
Eigen::Matrix<double, 1, 6> basisWeights(double u, int n) {
  Eigen::Matrix<double, 1, 6> powers = Eigen::Matrix<double, 1, 6>::Zero();
  for (int m = n; m <= kDegree; ++m) {
    powers(m) = factorial(m) / factorial(m - n) * std::pow(u, m - n);
  }
  return powers * QuinticBSpline::basisMatrix();
}

// Rows of the interpolation system: value at every knot, velocity and acceleration zero at ends.
Eigen::MatrixXd interpolationSystem(int segments) {
  const int n = segments + kDegree;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  // Knot k < segments starts segment k; the last knot is the end (u = 1) of the last segment.
  // NOTE: taking it as the start of a segment `segments` wrote a row one column past the matrix.
  for (int k = 0; k < segments; ++k) A.block(k, k, 1, 6) = basisWeights(0.0, 0);
  A.block(segments, segments - 1, 1, 6) = basisWeights(1.0, 0);
  A.block(segments + 1, 0, 1, 6) = basisWeights(0.0, 1);
  A.block(segments + 2, 0, 1, 6) = basisWeights(0.0, 2);
  A.block(segments + 3, segments - 1, 1, 6) = basisWeights(1.0, 1);
  A.block(segments + 4, segments - 1, 1, 6) = basisWeights(1.0, 2);
  return A;
}

}  // namespace

const Eigen::Matrix<double, 6, 6>& QuinticBSpline::basisMatrix() {
  static const Eigen::Matrix<double, 6, 6> kBasis = makeBasis();
  return kBasis;
}

QuinticBSpline::QuinticBSpline(const std::vector<Eigen::Vector3d>& points,
                               double segment_duration_s)
    : segment_duration_s_(segment_duration_s), segment_count_(static_cast<int>(points.size()) - 1) {
  if (points.size() < 2) throw InputError("QuinticBSpline: needs at least 2 points");
  if (!(segment_duration_s > 0.0) || !std::isfinite(segment_duration_s)) {
    throw InputError("QuinticBSpline: segment_duration_s must be positive and finite");
  }
  const int n = segment_count_ + kDegree;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 3);
  for (int k = 0; k <= segment_count_; ++k) {
    if (!points[k].allFinite())
      throw InputError("QuinticBSpline: point " + std::to_string(k) + " is not finite");
    rhs.row(k) = points[k].transpose();
  }
  const Eigen::MatrixXd control = interpolationSystem(segment_count_).partialPivLu().solve(rhs);
  control_points_.resize(n);
  for (int i = 0; i < n; ++i) control_points_[i] = control.row(i).transpose();
}

Eigen::Vector3d QuinticBSpline::evaluate(double t_s, int derivative) const {
  if (derivative < 0 || derivative > kDegree) {
    throw InputError("QuinticBSpline::evaluate: derivative must be 0..5");
  }
  const double s = t_s / segment_duration_s_;
  const int segment = std::clamp(static_cast<int>(std::floor(s)), 0, segment_count_ - 1);
  const Eigen::Matrix<double, 1, 6> w = basisWeights(s - segment, derivative);
  Eigen::Vector3d value = Eigen::Vector3d::Zero();
  for (int j = 0; j < 6; ++j) value += w(j) * control_points_[segment + j];
  return value / std::pow(segment_duration_s_, derivative);  // d/dt = (1 / dt) d/du
}

}  // namespace strata::sim
