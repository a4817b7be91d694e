#include "strata/sim/sensors/odometry_drift.h"

#include <cmath>

#include "strata/core/error.h"
#include "strata/sim/rng.h"

namespace strata::sim {
namespace {

// E_k: yaw by `yaw` about the vertical through `pivot_W`, then shift by `offset_W`:
// E(x) = Rz(yaw) (x - pivot) + pivot + offset.
Eigen::Isometry3d stepError(const Eigen::Vector3d& pivot_W, double yaw,
                            const Eigen::Vector3d& offset_W) {
  Eigen::Isometry3d E = Eigen::Isometry3d::Identity();
  E.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  E.translation() = pivot_W - E.linear() * pivot_W + offset_W;
  return E;
}

}  // namespace

void DriftConfig::validate() const {
  if (!(translation_sigma_m_per_sqrt_m >= 0.0) || !std::isfinite(translation_sigma_m_per_sqrt_m)) {
    throw InputError("DriftConfig: translation_sigma_m_per_sqrt_m must be finite and >= 0");
  }
  if (!(yaw_sigma_rad_per_sqrt_m >= 0.0) || !std::isfinite(yaw_sigma_rad_per_sqrt_m)) {
    throw InputError("DriftConfig: yaw_sigma_rad_per_sqrt_m must be finite and >= 0");
  }
}

std::vector<Eigen::Isometry3d> addOdometryDrift(const std::vector<Eigen::Isometry3d>& poses,
                                                const DriftConfig& config, std::uint64_t seed) {
  config.validate();
  std::vector<Eigen::Isometry3d> drifted;
  drifted.reserve(poses.size());
  Rng rng(seed);
  Eigen::Isometry3d D = Eigen::Isometry3d::Identity();  // E_1 o ... o E_k
  for (std::size_t k = 0; k < poses.size(); ++k) {
    if (k > 0) {
      const Eigen::Vector3d p = poses[k].translation();
      // Random walk: increments ~ N(0, sigma^2 d) for d metres travelled in this step.
      const double root_d = std::sqrt((p - poses[k - 1].translation()).norm());
      const double sigma_t = config.translation_sigma_m_per_sqrt_m * root_d;
      const Eigen::Vector3d offset(sigma_t * rng.normal(), sigma_t * rng.normal(),
                                   sigma_t * rng.normal());
      const double yaw = config.yaw_sigma_rad_per_sqrt_m * root_d * rng.normal();
      D = D * stepError(p, yaw, offset);
    }
    drifted.push_back(D * poses[k]);
  }
  return drifted;
}

}  // namespace strata::sim
