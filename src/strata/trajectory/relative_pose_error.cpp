#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "strata/trajectory/trajectory_error.h"

namespace strata::trajectory {
namespace {

double angleDeg(const Eigen::Matrix3d& R) {
  return Eigen::AngleAxisd(R).angle() * 180.0 / M_PI;
}

Eigen::Isometry3d scaledMotion(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to,
                               double scale) {
  Eigen::Isometry3d motion = from.inverse() * to;
  motion.translation() *= scale;
  return motion;
}

}  // namespace

void relativePoseError(const std::vector<Eigen::Isometry3d>& estimate,
                       const std::vector<Eigen::Isometry3d>& truth, double segment_m, double scale,
                       std::size_t* pairs, double* trans_percent, double* rot_deg_per_m) {
  // distance_m[i]: path length along the truth from pose 0 to pose i.
  std::vector<double> distance_m(truth.size(), 0.0);
  for (std::size_t i = 1; i < truth.size(); ++i) {
    distance_m[i] = distance_m[i - 1] + (truth[i].translation() - truth[i - 1].translation()).norm();
  }
  double trans_sq = 0.0, rot_sq = 0.0;
  std::size_t n = 0;
  std::size_t j = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    // NOTE: j only moves forward, so the scan is linear in the trajectory length.
    if (j < i) j = i;
    while (j < truth.size() && distance_m[j] - distance_m[i] < segment_m) ++j;
    if (j == truth.size()) break;
    const double length_m = distance_m[j] - distance_m[i];
    const Eigen::Isometry3d true_motion = truth[i].inverse() * truth[j];
    const Eigen::Isometry3d est_motion = scaledMotion(estimate[i], estimate[j], scale);
    const Eigen::Isometry3d error = true_motion.inverse() * est_motion;
    const double t = 100.0 * error.translation().norm() / length_m;
    const double r = angleDeg(error.linear()) / length_m;
    trans_sq += t * t;
    rot_sq += r * r;
    ++n;
  }
  *pairs = n;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  *trans_percent = n > 0 ? std::sqrt(trans_sq / static_cast<double>(n)) : nan;
  *rot_deg_per_m = n > 0 ? std::sqrt(rot_sq / static_cast<double>(n)) : nan;
}

}  // namespace strata::trajectory
