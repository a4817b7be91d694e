#include "strata/sim/sensors/odometry_frame.h"

#include <cmath>

#include "strata/core/error.h"
#include "strata/sim/rng.h"

namespace strata::sim {
namespace {

// Sub-stream of the seed for the frame ("OFRM"), apart from the drift's draws.
constexpr std::uint64_t kFrameStream = 0x4f46524dull;

void requireFrameNonNegative(double value, const char* field) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    throw InputError(std::string("OdometryFrameConfig: ") + field + " must be finite and >= 0");
  }
}

}  // namespace

void OdometryFrameConfig::validate() const {
  requireFrameNonNegative(horizontal_offset_m, "horizontal_offset_m");
  requireFrameNonNegative(vertical_offset_m, "vertical_offset_m");
}

Eigen::Isometry3d randomOdometryFrame(const OdometryFrameConfig& config, std::uint64_t seed) {
  config.validate();
  Rng rng = Rng::stream(seed, kFrameStream);
  const double yaw_rad = rng.uniform(-M_PI, M_PI);
  const double h = config.horizontal_offset_m;
  const double x_m = rng.uniform(-h, h);
  const double y_m = rng.uniform(-h, h);
  const double z_m = rng.uniform(-config.vertical_offset_m, config.vertical_offset_m);
  Eigen::Isometry3d T_W_S = Eigen::Isometry3d::Identity();
  T_W_S.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_W_S.translation() = Eigen::Vector3d(x_m, y_m, z_m);
  return T_W_S;
}

std::vector<Eigen::Isometry3d> posesInFrame(const Eigen::Isometry3d& T_S_W,
                                            const std::vector<Eigen::Isometry3d>& T_W_C) {
  std::vector<Eigen::Isometry3d> T_S_C;
  T_S_C.reserve(T_W_C.size());
  for (const Eigen::Isometry3d& pose : T_W_C) T_S_C.push_back(T_S_W * pose);
  return T_S_C;
}

}  // namespace strata::sim
