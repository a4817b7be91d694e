#include "strata/sim/sensors/imu.h"

#include <Eigen/LU>
#include <cmath>
#include <cstdio>
#include <string>

#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/sim/rng.h"

namespace strata::sim {
namespace {

constexpr char kEurocImuHeader[] =
    "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
    "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n";

Eigen::Matrix3d skew(const Eigen::Vector3d& w) {
  Eigen::Matrix3d S;
  S << 0.0, -w.z(), w.y(), w.z(), 0.0, -w.x(), -w.y(), w.x(), 0.0;
  return S;
}

Eigen::Vector3d gaussian3(Rng& rng) { return {rng.normal(), rng.normal(), rng.normal()}; }

void requireImuNonNegative(double value, const char* field) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    throw InputError(std::string("ImuConfig: ") + field + " must be finite and >= 0");
  }
}

}  // namespace

void ImuConfig::validate() const {
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) {
    throw InputError("ImuConfig: rate_hz must be positive and finite");
  }
  requireImuNonNegative(gyro_noise_density, "gyro_noise_density");
  requireImuNonNegative(gyro_random_walk, "gyro_random_walk");
  requireImuNonNegative(accel_noise_density, "accel_noise_density");
  requireImuNonNegative(accel_random_walk, "accel_random_walk");
  requireImuNonNegative(gravity_mps2, "gravity_mps2");
  if (!initial_gyro_bias.allFinite() || !initial_accel_bias.allFinite()) {
    throw InputError("ImuConfig: initial biases must be finite");
  }
  const Eigen::Matrix3d R = T_C_B.linear();
  if (!T_C_B.matrix().allFinite() ||
      (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-6 || R.determinant() < 0.0) {
    throw InputError("ImuConfig: T_C_B must be a finite rigid transform");
  }
}

void idealImu(const TrajectoryState& state, const ImuConfig& config, Eigen::Vector3d* gyro_rad_s,
              Eigen::Vector3d* accel_mps2) {
  const Eigen::Matrix3d R_W_C = state.T_W_C.linear();
  const Eigen::Matrix3d R_C_B = config.T_C_B.linear();
  const Eigen::Vector3d& w = state.angular_velocity_C;
  // d^2/dt^2 (R_W_C t_C_B) = R_W_C ([alpha]x + [w]x [w]x) t_C_B for body-frame rates.
  const Eigen::Vector3d a_B_W =
      state.acceleration_W +
      R_W_C * (skew(state.angular_acceleration_C) + skew(w) * skew(w)) * config.T_C_B.translation();
  const Eigen::Vector3d g_W(0.0, 0.0, -config.gravity_mps2);
  *gyro_rad_s = R_C_B.transpose() * w;
  *accel_mps2 = (R_W_C * R_C_B).transpose() * (a_B_W - g_W);
}

std::vector<ImuSample> simulateImu(const Trajectory& trajectory, const ImuConfig& config,
                                   std::uint64_t seed) {
  config.validate();
  const double dt = 1.0 / config.rate_hz;
  // Discrete-time sigmas (Kalibr): white sigma_d = sigma_c / sqrt(dt); walk sigma_bd = sigma_bc
  // sqrt(dt).
  const double gyro_sigma = config.noise ? config.gyro_noise_density / std::sqrt(dt) : 0.0;
  const double accel_sigma = config.noise ? config.accel_noise_density / std::sqrt(dt) : 0.0;
  const double gyro_walk = config.noise ? config.gyro_random_walk * std::sqrt(dt) : 0.0;
  const double accel_walk = config.noise ? config.accel_random_walk * std::sqrt(dt) : 0.0;
  Rng rng(seed);
  Eigen::Vector3d gyro_bias = config.initial_gyro_bias;
  Eigen::Vector3d accel_bias = config.initial_accel_bias;
  std::vector<ImuSample> samples;
  for (double t : trajectory.sampleTimes(config.rate_hz)) {
    ImuSample s;
    s.t_s = t;
    s.timestamp_ns = config.start_time_ns + std::llround(t * 1e9);
    idealImu(trajectory.state(t), config, &s.gyro_rad_s, &s.accel_mps2);
    s.gyro_bias = gyro_bias;
    s.accel_bias = accel_bias;
    s.gyro_rad_s += gyro_bias + gyro_sigma * gaussian3(rng);
    s.accel_mps2 += accel_bias + accel_sigma * gaussian3(rng);
    gyro_bias += gyro_walk * gaussian3(rng);
    accel_bias += accel_walk * gaussian3(rng);
    samples.push_back(s);
  }
  return samples;
}

void writeImuCsv(const std::string& path, const std::vector<ImuSample>& samples) {
  std::string text = kEurocImuHeader;
  char line[512];
  for (const ImuSample& s : samples) {
    const int n =
        std::snprintf(line, sizeof(line), "%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                      static_cast<long long>(s.timestamp_ns), s.gyro_rad_s.x(), s.gyro_rad_s.y(),
                      s.gyro_rad_s.z(), s.accel_mps2.x(), s.accel_mps2.y(), s.accel_mps2.z());
    text.append(line, static_cast<std::size_t>(n));
  }
  writeFileAtomically(path, std::vector<std::uint8_t>(text.begin(), text.end()));
}

}  // namespace strata::sim
