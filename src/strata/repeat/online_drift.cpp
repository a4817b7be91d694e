#include "strata/repeat/online_drift.h"

#include <cmath>

namespace strata::repeat {

OnlineDrift::OnlineDrift(const sim::DriftConfig& config, std::uint64_t seed)
    : config_(config), rng_(seed) {
  config_.validate();
}

Eigen::Isometry3d OnlineDrift::next(const Eigen::Isometry3d& T_W_C) {
  const Eigen::Vector3d p = T_W_C.translation();
  if (!first_) {
    const double d = (p - last_p_W_).norm();
    distance_m_ += d;
    const double root_d = std::sqrt(d);
    const double sigma_t = config_.translation_sigma_m_per_sqrt_m * root_d;
    const Eigen::Vector3d offset(sigma_t * rng_.normal(), sigma_t * rng_.normal(),
                                 sigma_t * rng_.normal());
    const double yaw = config_.yaw_sigma_rad_per_sqrt_m * root_d * rng_.normal();
    // E(x) = Rz(yaw) (x - p) + p + offset, as sim::addOdometryDrift's step error.
    Eigen::Isometry3d E = Eigen::Isometry3d::Identity();
    E.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    E.translation() = p - E.linear() * p + offset;
    D_ = D_ * E;
  }
  first_ = false;
  last_p_W_ = p;
  return D_ * T_W_C;
}

}  // namespace strata::repeat
